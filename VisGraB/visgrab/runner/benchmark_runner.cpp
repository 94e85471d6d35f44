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

#include "rw/common/stop_signals.hpp"
#include "rw/common/strings.hpp"
#include "rw/common/task_pool.hpp"
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

namespace {

/// What a run reads before it starts.
struct RunInputs {
  database::Database db;
  std::vector<const database::SceneEntry*> selected;
  std::unique_ptr<grasp::HandGraspSetup> hand;
  taskio::GraspFileContents grasps;
};

/// The run's work: its scenes and methods (run.csv), the grasps per scene in benchmark order and
/// the grasps rejected so far.
struct RunPlan {
  results::RunResults run;
  std::vector<SceneWork> work;
  std::vector<Diagnostic> rejected;
  /// Rejected grasps per method (per file for grasps the reader could not parse).
  std::map<std::string, int> rejectedPerMethod;
};

/// The scenes with trials left to run, and the progress counters of the run.
struct PendingWork {
  std::vector<const SceneWork*> scenes;
  RunProgress progress;
};

/// Opens the database, the hand and the grasp files; refuses a result folder that holds
/// results unless resuming.
RunInputs openInputs(const RunOptions& options) {
  RunInputs in{database::Database::openAny(options.database), {}, {}, {}};
  in.selected = selectScenes(in.db, options.scenes);
  in.hand = grasp::loadHandGraspSetup(options.hand);
  in.grasps = taskio::readGraspSources(options.grasps);
  if (!options.resume && fs::exists(options.out / results::kTrialsFileName)) {
    throw std::runtime_error(options.out.string() +
                             " already holds results; resume them (--resume) or choose another "
                             "folder");
  }
  return in;
}

/// Groups the grasps by selected scene (database order), ranks them per (scene, method) in file
/// order and orders each scene's by (method first seen, rank); rejects grasps of unknown scenes.
RunPlan planRun(const RunOptions& options, const RunInputs& in) {
  RunPlan plan;
  plan.rejected = in.grasps.rejected;
  // Grasps the reader could not parse have no reliable method: they count under their file.
  for (const auto& d : in.grasps.rejected) {
    ++plan.rejectedPerMethod[fs::path(d.file).filename().string()];
  }
  results::RunResults& run = plan.run;
  run.sources.database = fs::absolute(options.database).lexically_normal();
  for (const auto& g : options.grasps) {
    run.sources.grasps.push_back(fs::absolute(g).lexically_normal());
  }
  run.sources.hand = fs::absolute(options.hand).lexically_normal();
  std::map<std::string, std::size_t> sceneOrder;
  for (const auto* s : in.selected) {
    sceneOrder.emplace(s->id, run.scenes.size());
    run.scenes.push_back({s->id, s->conditions});
  }
  plan.work.resize(run.scenes.size());
  std::map<std::pair<std::string, std::string>, int> ranks;
  for (const auto& r : in.grasps.requests) {
    if (!in.db.contains(r.sceneId)) {
      const auto close = in.db.closestIds(r.sceneId);
      std::string hint = close.empty() ? "" : " (did you mean " + close.front() + "?)";
      plan.rejected.push_back(rejection(r, "unknown scene \"" + r.sceneId + "\"" + hint));
      ++plan.rejectedPerMethod[r.method];
      continue;
    }
    const auto& entry = in.db.scene(r.sceneId);
    const auto it = sceneOrder.find(entry.id);
    if (it == sceneOrder.end()) continue;  // filtered out
    if (std::find(run.methods.begin(), run.methods.end(), r.method) == run.methods.end()) {
      run.methods.push_back(r.method);
    }
    SceneWork& w = plan.work[it->second];
    w.entry = &entry;
    w.jobs.push_back({&r, ranks[{entry.id, r.method}]++});
  }
  // Within a scene: methods in the order first seen, then rank.
  for (auto& w : plan.work) {
    std::stable_sort(w.jobs.begin(), w.jobs.end(), [&](const Job& a, const Job& b) {
      const auto ia = std::find(run.methods.begin(), run.methods.end(), a.request->method);
      const auto ib = std::find(run.methods.begin(), run.methods.end(), b.request->method);
      return ia < ib;
    });
  }
  return plan;
}

/// The scenes with trials not yet in `writer` (resume) and how many trials they hold.
PendingWork pendingScenes(const std::vector<SceneWork>& work,
                          const results::ResultsWriter& writer) {
  PendingWork pending;
  for (const auto& w : work) {
    const auto left = std::count_if(w.jobs.begin(), w.jobs.end(), [&](const Job& j) {
      return !writer.contains(w.entry->id, j.request->method, j.request->id);
    });
    if (left == 0) continue;
    pending.scenes.push_back(&w);
    pending.progress.trialsTotal += static_cast<int>(left);
  }
  pending.progress.scenesTotal = static_cast<int>(pending.scenes.size());
  return pending;
}

/// Writes run.csv with the plan's scenes, methods and rejected counts so far.
void writeRunFile(RunPlan& plan, results::ResultsWriter& writer) {
  plan.run.rejected.clear();
  for (const auto& [method, n] : plan.rejectedPerMethod) plan.run.rejected.emplace_back(method, n);
  writer.writeRun(plan.run);
}

/// A hand that does not fit (a missing dynamics file, a device or controller the scene's
/// dynamics lack) fails every scene: reported once, as the run's error, not per grasp.
void checkHandFits(const PendingWork& pending, const grasp::HandGraspSetup& hand,
                   const fs::path& handFile) {
  if (pending.scenes.empty()) return;
  try {
    const SceneRunner probe(*pending.scenes.front(), hand);
  } catch (const rw::common::LoadError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error("the hand " + handFile.string() + " cannot run in scene " +
                             pending.scenes.front()->entry->id + ": " + e.what());
  }
}

/// What a scene reports per grasp done: the grasp, and its rejection if it was rejected as input.
using TrialDone = std::function<void(const grasp::GraspRequest&, const std::optional<Diagnostic>&)>;

/// Runs one scene's trials that are not in `writer` yet, appending each as it finishes;
/// `trialDone` gets each grasp done and its rejection if it was rejected as input (nullopt for
/// a trial). Returns false early, between trials, once `stopping` says so. A scene file that
/// cannot be read throws rw::common::LoadError; a scene the hand cannot be put in rejects its
/// grasps.
bool runScene(const SceneWork& w, const grasp::HandGraspSetup& hand, results::ResultsWriter& writer,
              const std::function<bool()>& stopping, const TrialDone& trialDone) {
  std::unique_ptr<SceneRunner> runner;
  std::string failure;
  try {
    runner = std::make_unique<SceneRunner>(w, hand);
  } catch (const rw::common::LoadError&) {
    throw;  // an unreadable or broken scene file: the run stops (and resumes once it is mended)
  } catch (const std::exception& e) {
    failure = e.what();
  }
  for (const Job& job : w.jobs) {
    if (stopping()) return false;
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
    trialDone(r, record ? std::nullopt : std::optional<Diagnostic>(rejected));
  }
  return true;
}

/// Runs the pending scenes on options.threads workers (a scene per task), counting rejections
/// into `plan`. A set options.stop, or an error in any scene (a scene file that cannot be read,
/// a failed write), ends every scene after its current trial; no new scene starts; the first
/// error is thrown.
void runScenes(const RunOptions& options, const grasp::HandGraspSetup& hand, PendingWork& pending,
               RunPlan& plan, results::ResultsWriter& writer, const std::function<void()>& report) {
  std::mutex mutex;
  std::atomic<bool> failing{false};
  const auto stopping = [&] {
    return failing.load() || (options.stop != nullptr && options.stop->load());
  };
  const auto trialDone = [&](const grasp::GraspRequest& r,
                             const std::optional<Diagnostic>& rejected) {
    const std::lock_guard lock(mutex);
    if (rejected) {
      plan.rejected.push_back(*rejected);
      ++plan.rejectedPerMethod[r.method];
    }
    ++pending.progress.trialsDone;
    report();
  };
  const rw::common::TaskPool pool(
      std::min<int>(options.threads, static_cast<int>(pending.scenes.size())), options.stop);
  pool.run(pending.scenes.size(), [&](std::size_t i, int /*worker*/) {
    bool complete = false;
    try {
      complete = runScene(*pending.scenes[i], hand, writer, stopping, trialDone);
    } catch (...) {
      failing = true;
      throw;
    }
    if (!complete) return;
    const std::lock_guard lock(mutex);
    ++pending.progress.scenesDone;
    report();
  });
}

/// Rewrites run.csv with the final rejected counts, puts trials.csv in canonical order and sums
/// the run up.
RunSummary finishRun(RunPlan& plan, results::ResultsWriter& writer) {
  writeRunFile(plan, writer);
  writer.finalize();
  RunSummary summary;
  summary.resumed = static_cast<int>(writer.resumedCount());
  for (const auto& t : writer.trials()) {
    ++summary.outcomes[std::string(rwsim::simulator::outcomeName(t.outcome))];
    ++summary.trials;
  }
  summary.trials -= summary.resumed;
  summary.scenes = static_cast<int>(plan.run.scenes.size());
  summary.methods = static_cast<int>(plan.run.methods.size());
  summary.rejected = std::move(plan.rejected);
  std::stable_sort(summary.rejected.begin(), summary.rejected.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     return std::tie(a.file, a.line) < std::tie(b.file, b.line);
                   });
  return summary;
}

}  // namespace

RunSummary runBenchmark(const RunOptions& options,
                        const std::function<void(const RunProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const RunInputs in = openInputs(options);
  RunPlan plan = planRun(options, in);
  results::ResultsWriter writer(options.out);
  PendingWork pending = pendingScenes(plan.work, writer);
  writeRunFile(plan, writer);
  checkHandFits(pending, *in.hand, options.hand);
  runScenes(options, *in.hand, pending, plan, writer, [&] {
    pending.progress.elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress(pending.progress);
  });
  if (pending.progress.trialsDone < pending.progress.trialsTotal) {
    // Only a stop request leaves trials undone (errors throw): trials.csv keeps the finished
    // ones in the order they finished; --resume runs the rest and puts them in order.
    throw rw::common::StopRequested(
        "stopped after " + std::to_string(pending.progress.trialsDone) + " of " +
        std::to_string(pending.progress.trialsTotal) + " trials; the finished ones are in " +
        (options.out / results::kTrialsFileName).string() + "; --resume continues the run");
  }
  return finishRun(plan, writer);
}

}  // namespace visgrab::runner
