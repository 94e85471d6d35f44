#include "visgrab/runner/benchmark_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/results_writer.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::runner {

namespace {

namespace fs = std::filesystem;
using rw::common::Diagnostic;
using rwsim::simulator::GraspOutcome;

/// One grasp to run: its request and its rank among its scene's grasps of its method.
struct Job {
  const grasp::GraspRequest* request = nullptr;
  int rank = 0;
};

/// A scene with its grasps, in (method first seen, rank) order.
struct SceneWork {
  const database::SceneEntry* entry = nullptr;
  std::vector<Job> jobs;
};

Diagnostic rejection(const grasp::GraspRequest& r, const std::string& message) {
  Diagnostic d;
  d.file = r.sourceFile;
  d.line = r.sourceLine;
  d.message = "grasp " + r.id + ": " + message;
  return d;
}

std::vector<const database::SceneEntry*> selectScenes(const database::Database& db,
                                                      const std::string& filterText) {
  try {
    return db.filter(filterText.empty() ? database::SceneFilter()
                                        : database::SceneFilter::parse(filterText));
  } catch (const database::FilterError& e) {
    throw std::invalid_argument(std::string("scene filter: ") + e.what());
  }
}

int objectIdOf(const rwsim::dynamics::DynamicWorkCell& dwc, rwsim::dynamics::BodyId body) {
  if (!body.valid()) return 0;
  const std::string& name = dwc.body(body).name;
  return database::objectIdByName(name).value_or(0);
}

/// Runs one scene's pending jobs; appends each trial as it finishes.
class SceneRunner {
 public:
  SceneRunner(const SceneWork& work, const grasp::HandGraspSetup& hand)
      : work_(&work), hand_(&hand) {
    dwc_ = loadSceneWithHand(*work.entry, hand);
    trial_ = std::make_unique<rwsim::simulator::GraspTrial>(*dwc_, trialSetup(hand, *dwc_));
  }

  /// The trial record of `job`, or nullopt (and `rejected` set) for a grasp rejected as input.
  std::optional<results::TrialRecord> run(const Job& job, Diagnostic& rejected) const {
    const grasp::GraspRequest& r = *job.request;
    const grasp::ResolvedGrasp resolved =
        grasp::resolve(r, *hand_, [this](const rwsim::simulator::GraspParameters& g) {
          return trial_->checkPlacement(g, dwc_->workcell().defaultState());
        });
    if (resolved.status == grasp::ResolveStatus::kInputError) {
      rejected = rejection(r, resolved.message);
      return std::nullopt;
    }
    results::TrialRecord record;
    record.sceneId = work_->entry->id;
    record.conditions = work_->entry->conditions;
    record.method = r.method;
    record.graspId = r.id;
    record.rank = job.rank;
    if (resolved.status == grasp::ResolveStatus::kInvalidContacts ||
        resolved.status == grasp::ResolveStatus::kInCollision) {
      // Nothing to simulate: the contact IK found no configuration, or the placement search
      // no collision-free placement (the message gives the least penetration).
      record.outcome = resolved.status == grasp::ResolveStatus::kInCollision
                           ? GraspOutcome::kInCollision
                           : GraspOutcome::kInvalidContacts;
      record.detail = resolved.message;
      return record;
    }
    const auto result = trial_->run(resolved.parameters, dwc_->workcell().defaultState());
    record.outcome = result.outcome;
    record.qLift = result.qLift;
    record.qGws = result.qGws;
    record.qGwsUnit = result.qGwsUnit;
    record.object = objectIdOf(*dwc_, result.object);
    record.simulatedTime = result.simulatedTime;
    record.detail = result.detail;
    if (resolved.placement && resolved.placement->tests > 1) {
      record.detail += "; " + resolved.placement->describe();
    }
    return record;
  }

 private:
  const SceneWork* work_;
  const grasp::HandGraspSetup* hand_;
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc_;
  std::unique_ptr<rwsim::simulator::GraspTrial> trial_;
};

}  // namespace

namespace {

/// One `<Include file="..."/>` of a scene file.
struct IncludeRef {
  std::size_t valueBegin = 0, valueEnd = 0;
  fs::path target;
};

/// The Includes of `text` (a scene file in `folder`) whose target lies in a folder "hands"
/// (`<Include file="..."/>` as the generator writes them).
std::vector<IncludeRef> handIncludes(const std::string& text, const fs::path& folder) {
  std::vector<IncludeRef> out;
  constexpr std::string_view kTag = "<Include";
  constexpr std::string_view kAttribute = "file=\"";
  for (std::size_t at = text.find(kTag); at != std::string::npos; at = text.find(kTag, at + 1)) {
    const std::size_t close = text.find('>', at);
    const std::size_t attr = text.find(kAttribute, at);
    if (close == std::string::npos || attr == std::string::npos || attr > close) continue;
    const std::size_t begin = attr + kAttribute.size();
    const std::size_t end = text.find('"', begin);
    if (end == std::string::npos || end > close) continue;
    const fs::path target = (folder / text.substr(begin, end - begin)).lexically_normal();
    if (target.parent_path().parent_path().filename() != "hands") continue;
    out.push_back(IncludeRef{begin, end, target});
  }
  return out;
}

bool sameContent(const fs::path& a, const fs::path& b) {
  std::string ta, tb;
  return rw::common::readTextFile(a, ta).empty() && rw::common::readTextFile(b, tb).empty() &&
         ta == tb;
}

}  // namespace

std::unique_ptr<rwsim::dynamics::DynamicWorkCell> loadSceneWithHand(
    const database::SceneEntry& entry, const grasp::HandGraspSetup& hand) {
  if (hand.workcellFile().empty() || hand.dynamicsFile().empty()) {
    return rwsim::loaders::loadDynamicWorkCell(entry.dynamicWorkcell);
  }
  const std::string wcText = rw::common::readTextFileOrThrow(entry.workcell);
  const std::string dwcText = rw::common::readTextFileOrThrow(entry.dynamicWorkcell);
  const auto wcRefs = handIncludes(wcText, entry.workcell.parent_path());
  const auto dwcRefs = handIncludes(dwcText, entry.dynamicWorkcell.parent_path());
  if (wcRefs.size() != 1 || dwcRefs.size() != 1) {
    // Not a generated scene (an original or hand-written one): usable as it is when it holds
    // the hand already.
    auto dwc = rwsim::loaders::loadDynamicWorkCell(entry.dynamicWorkcell);
    if (dwc->findDevice(hand.deviceName()).valid()) return dwc;
    throw std::runtime_error(
        "scene " + entry.id + " has no device '" + hand.deviceName() + "' and does not include a " +
        "hand from a hands/<hand>/ folder once in " + entry.workcell.filename().string() +
        " and once in " + entry.dynamicWorkcell.filename().string() + " (found " +
        std::to_string(wcRefs.size()) + " and " + std::to_string(dwcRefs.size()) +
        "); cannot put the hand " + hand.description().file + " in");
  }
  const IncludeRef& wcRef = wcRefs.front();
  const IncludeRef& dwcRef = dwcRefs.front();
  if (sameContent(wcRef.target, hand.workcellFile()) &&
      sameContent(dwcRef.target, hand.dynamicsFile())) {
    return rwsim::loaders::loadDynamicWorkCell(entry.dynamicWorkcell);
  }
  if (!fs::is_regular_file(hand.dynamicsFile())) {
    throw std::runtime_error("the hand's dynamics file " + hand.dynamicsFile().string() +
                             " is missing (GraspDescription dynamics=\"...\"; default: the "
                             "workcell's name up to its first dot + _dynamics.dwc.xml)");
  }
  std::string wc = wcText;
  wc.replace(wcRef.valueBegin, wcRef.valueEnd - wcRef.valueBegin,
             rw::common::escapeXml(hand.workcellFile().generic_string()));
  std::string dwc = dwcText;
  dwc.replace(dwcRef.valueBegin, dwcRef.valueEnd - dwcRef.valueBegin,
              rw::common::escapeXml(hand.dynamicsFile().generic_string()));
  return rwsim::loaders::loadDynamicWorkCellFromStrings(dwc, wc, entry.dynamicWorkcell);
}

rwsim::simulator::GraspTrialSetup trialSetup(const grasp::HandGraspSetup& hand,
                                             const rwsim::dynamics::DynamicWorkCell& dwc) {
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = hand.deviceName();
  setup.controller = hand.controllerName();
  setup.tcpFrame = hand.tcpFrameName();
  setup.simulator = rwsim::simulator::optionsFromEngineProperties(dwc);
  return setup;
}

RunSummary runBenchmark(const RunOptions& options,
                        const std::function<void(const RunProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const database::Database db = database::Database::openAny(options.database);
  const auto selected = selectScenes(db, options.scenes);
  const auto hand = grasp::loadHandGraspSetup(options.hand);
  const taskio::GraspFileContents grasps = taskio::readGraspSources(options.grasps);
  if (!options.resume && fs::exists(options.out / results::kTrialsFileName)) {
    throw std::runtime_error(options.out.string() +
                             " already holds results; resume them (--resume) or choose another "
                             "folder");
  }

  RunSummary summary;
  summary.rejected = grasps.rejected;
  std::map<std::string, int> rejectedPerMethod;
  // Grasps the reader could not parse have no reliable method: they count under their file.
  for (const auto& d : grasps.rejected) ++rejectedPerMethod[fs::path(d.file).filename().string()];
  results::RunResults run;
  run.sources.database = fs::absolute(options.database).lexically_normal();
  for (const auto& g : options.grasps) {
    run.sources.grasps.push_back(fs::absolute(g).lexically_normal());
  }
  run.sources.hand = fs::absolute(options.hand).lexically_normal();
  std::map<std::string, std::size_t> sceneOrder;
  for (const auto* s : selected) {
    sceneOrder.emplace(s->id, run.scenes.size());
    run.scenes.push_back({s->id, s->conditions});
  }
  // Group the grasps by scene; rank them per (scene, method) in file order.
  std::vector<SceneWork> work(run.scenes.size());
  std::map<std::pair<std::string, std::string>, int> ranks;
  for (const auto& r : grasps.requests) {
    if (!db.contains(r.sceneId)) {
      const auto close = db.closestIds(r.sceneId);
      std::string hint = close.empty() ? "" : " (did you mean " + close.front() + "?)";
      summary.rejected.push_back(rejection(r, "unknown scene \"" + r.sceneId + "\"" + hint));
      ++rejectedPerMethod[r.method];
      continue;
    }
    const auto& entry = db.scene(r.sceneId);
    const auto it = sceneOrder.find(entry.id);
    if (it == sceneOrder.end()) continue;  // filtered out
    if (std::find(run.methods.begin(), run.methods.end(), r.method) == run.methods.end()) {
      run.methods.push_back(r.method);
    }
    SceneWork& w = work[it->second];
    w.entry = &entry;
    w.jobs.push_back({&r, ranks[{entry.id, r.method}]++});
  }
  // Within a scene: methods in the order first seen, then rank.
  for (auto& w : work) {
    std::stable_sort(w.jobs.begin(), w.jobs.end(), [&](const Job& a, const Job& b) {
      const auto ia = std::find(run.methods.begin(), run.methods.end(), a.request->method);
      const auto ib = std::find(run.methods.begin(), run.methods.end(), b.request->method);
      return ia < ib;
    });
  }

  results::ResultsWriter writer(options.out);
  summary.resumed = static_cast<int>(writer.resumedCount());
  std::vector<const SceneWork*> pending;
  RunProgress state;
  for (const auto& w : work) {
    const auto left = std::count_if(w.jobs.begin(), w.jobs.end(), [&](const Job& j) {
      return !writer.contains(w.entry->id, j.request->method, j.request->id);
    });
    if (left == 0) continue;
    pending.push_back(&w);
    state.trialsTotal += static_cast<int>(left);
  }
  state.scenesTotal = static_cast<int>(pending.size());
  for (const auto& [method, n] : rejectedPerMethod) run.rejected.emplace_back(method, n);
  writer.writeRun(run);

  // A hand that does not fit (a missing dynamics file, a device or controller the scene's
  // dynamics lack) fails every scene: report it once, as the run's error, not per grasp.
  if (!pending.empty()) {
    try {
      SceneRunner probe(*pending.front(), *hand);
    } catch (const rw::common::LoadError&) {
      throw;
    } catch (const std::exception& e) {
      throw std::runtime_error("the hand " + options.hand.string() + " cannot run in scene " +
                               pending.front()->entry->id + ": " + e.what());
    }
  }

  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  auto report = [&]() {
    state.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(state);
  };
  auto worker = [&]() {
    for (std::size_t i = next++; i < pending.size(); i = next++) {
      const SceneWork& w = *pending[i];
      std::unique_ptr<SceneRunner> runner;
      std::string failure;
      try {
        runner = std::make_unique<SceneRunner>(w, *hand);
      } catch (const std::exception& e) {
        failure = e.what();
      }
      for (const Job& job : w.jobs) {
        const auto& r = *job.request;
        if (writer.contains(w.entry->id, r.method, r.id)) continue;
        Diagnostic rejected;
        std::optional<results::TrialRecord> record;
        if (runner) {
          record = runner->run(job, rejected);
        } else {
          rejected = rejection(r, "scene " + w.entry->id + " cannot be simulated: " + failure);
        }
        if (record) writer.append(*record);
        const std::lock_guard lock(mutex);
        if (!record) {
          summary.rejected.push_back(rejected);
          ++rejectedPerMethod[r.method];
        }
        ++state.trialsDone;
        report();
      }
      const std::lock_guard lock(mutex);
      ++state.scenesDone;
      report();
    }
  };
  const int threads = std::max(
      1,
      std::min<int>(options.threads, static_cast<int>(std::max<std::size_t>(1, pending.size()))));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  run.rejected.clear();
  for (const auto& [method, n] : rejectedPerMethod) run.rejected.emplace_back(method, n);
  writer.writeRun(run);
  writer.finalize();
  for (const auto& t : writer.trials()) {
    ++summary.outcomes[std::string(rwsim::simulator::outcomeName(t.outcome))];
    ++summary.trials;
  }
  summary.trials -= summary.resumed;
  summary.scenes = static_cast<int>(run.scenes.size());
  summary.methods = static_cast<int>(run.methods.size());
  std::stable_sort(summary.rejected.begin(), summary.rejected.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     return std::tie(a.file, a.line) < std::tie(b.file, b.line);
                   });
  return summary;
}

}  // namespace visgrab::runner
