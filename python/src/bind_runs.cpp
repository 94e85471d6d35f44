#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <cstdint>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "common.hpp"
#include "rw/common/diagnostic.hpp"
#include "rwsim/engines/engine_registry.hpp"
#include "visgrab/analysis/analysis.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/results/trial_columns.hpp"
#include "visgrab/runner/benchmark_runner.hpp"
#include "visgrab/taskio/grasp_list.hpp"
#include "visgrab/view/report_pictures.hpp"

namespace visgrab::python {

namespace {

namespace fs = std::filesystem;
using results::TrialRecord;

std::string quoted(const std::string& s) { return py::repr(py::str(s)).cast<std::string>(); }

// Every grasp of the grasp list `file` that the run would reject as input, as the run would
// report it (file:line and the same words): malformed lines, unknown scenes, pre-shapes the
// hand does not know, wrong numbers of joint values. Contact grasps are solved in the run.
std::vector<std::string> graspProblems(const OpenDatabase& d, const Hand& hand,
                                       const fs::path& file) {
  const taskio::GraspFileContents read = taskio::readGraspList(file);
  std::vector<std::string> problems;
  for (const auto& r : read.rejected) problems.push_back(r.format());
  for (const grasp::GraspRequest& r : read.requests) {
    rw::common::Diagnostic problem;
    problem.file = r.sourceFile;
    problem.line = r.sourceLine;
    if (!d.db->contains(r.sceneId)) {
      problem.message = "grasp " + r.id + ": " + runner::unknownSceneReason(*d.db, r.sceneId);
      problems.push_back(problem.format());
      continue;
    }
    if (r.kind == grasp::GraspKind::kContacts) continue;
    const grasp::ResolvedGrasp resolved = grasp::resolve(r, *hand.setup);
    if (resolved.status == grasp::ResolveStatus::kInputError) {
      problem.message = "grasp " + r.id + ": " + resolved.reason;
      problems.push_back(problem.format());
    }
  }
  return problems;
}

py::dict summaryDict(const runner::RunSummary& s) {
  py::dict d;
  d["trials"] = s.trials;
  d["resumed"] = s.resumed;
  std::vector<std::string> rejected;
  for (const auto& r : s.rejected) rejected.push_back(r.format());
  d["rejected"] = rejected;
  d["outcomes"] = s.outcomes;
  d["scenes"] = s.scenes;
  d["methods"] = s.methods;
  return d;
}

py::dict runBenchmark(const fs::path& database, const fs::path& grasps, const fs::path& out,
                      const fs::path& hand, const std::string& scenes, int threads, bool resume,
                      const std::string& engine, const py::object& progress, int repeats,
                      const fs::path& noise, long long seed, bool adaptive,
                      const fs::path& protocol) {
  if (threads < 1) throw py::value_error("threads must be >= 1, got " + std::to_string(threads));
  if (repeats < 1 || repeats > results::kMaxRepeats) {
    throw py::value_error("repeats must be between 1 and " + std::to_string(results::kMaxRepeats) +
                          ", got " + std::to_string(repeats));
  }
  if (seed < 0) throw py::value_error("seed must be >= 0, got " + std::to_string(seed));
  if (repeats == 1 && (!noise.empty() || adaptive)) {
    throw py::value_error(std::string(adaptive ? "adaptive" : "noise") +
                          " needs repeats > 1 (repeat 0 is the unperturbed trial)");
  }
  runner::RunOptions options;
  if (adaptive && repeats > 1) {
    // The runner's own check names the CLI's --repeats: the same rule, in the Python names.
    const int decideAfter = results::repeatsToDecide(options.adaptiveAlpha, options.adaptiveMargin);
    const int needed =
        results::minimumAdaptiveRepeats(options.adaptiveAlpha, options.adaptiveMargin);
    if (repeats < needed) {
      throw py::value_error(
          "adaptive: the adaptive rule (alpha " + results::formatDouble(options.adaptiveAlpha) +
          ", margin " + results::formatDouble(options.adaptiveMargin) + ") decides after " +
          std::to_string(decideAfter) +
          " agreeing perturbed trials, so with repeats=" + std::to_string(repeats) +
          " it never stops a grasp early: give repeats=" + std::to_string(needed) + " or more");
    }
  }
  try {
    rwsim::engines::checkEngine(engine);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("engine: ") + e.what());
  }
  options.database = database;
  options.grasps = {grasps};
  options.out = out;
  options.hand = hand;
  options.scenes = scenes;
  options.threads = threads;
  options.resume = resume;
  options.engine = engine;
  options.repeats = repeats;
  options.noise = noise;
  options.noiseSeed = static_cast<std::uint64_t>(seed);
  options.adaptive = adaptive;
  options.protocol = protocol;
  std::mutex mutex;
  runner::RunProgress latest;
  bool fresh = false;
  const auto tick = [&] {
    runner::RunProgress p;
    {
      const std::lock_guard lock(mutex);
      if (!fresh) return;
      fresh = false;
      p = latest;
    }
    progress(p.trialsDone, p.trialsTotal);
  };
  const runner::RunSummary summary = runInterruptible(
      [&](const std::atomic<bool>* stop) {
        options.stop = stop;
        return runner::runBenchmark(options, [&](const runner::RunProgress& p) {
          const std::lock_guard lock(mutex);
          latest = p;
          fresh = true;
        });
      },
      progress.is_none() ? std::function<void()>() : std::function<void()>(tick));
  return summaryDict(summary);
}

py::object conditionsOf(const std::optional<database::SceneConditions>& c) {
  if (!c) return py::none();
  py::dict d;
  d["texture"] = std::string(database::toString(c->texture));
  d["kind"] = std::string(database::toString(c->kind));
  d["arrangement"] = std::string(database::toString(c->arrangement()));
  d["object_ids"] = c->objects;
  d["pose"] = c->pose;
  return d;
}

std::string trialRepr(const TrialRecord& t) {
  return "visgrab.TrialResult(scene=" + quoted(t.sceneId) + ", method=" + quoted(t.method) +
         ", id=" + quoted(t.graspId) + ", rank=" + std::to_string(t.rank) +
         ", outcome=" + quoted(std::string(rwsim::trial::outcomeName(t.outcome))) +
         ", q_lift=" + py::repr(py::float_(t.qLift)).cast<std::string>() +
         ", q_gws=" + py::repr(py::float_(t.qGws)).cast<std::string>() + ")";
}

results::RunResults readResults(const fs::path& dir, std::vector<std::string>& warnings) {
  std::vector<rw::common::Diagnostic> found;
  results::RunResults run;
  {
    py::gil_scoped_release release;
    run = results::readResults(dir, &found);
  }
  for (const auto& w : found) warnings.push_back(w.format());
  return run;
}

}  // namespace

void bindRuns(py::module_& m) {
  py::class_<TrialRecord> trial(m, "TrialResult", R"doc(
One grasp trial of a run: a row of trials.csv (docs/report.md), read by the C++ results reader.
Its properties are trials.csv's columns (results::trialColumns(), the per-trial record's one
definition; the grasp column is `id`), plus `success` and `conditions`.
)doc");
  for (const results::TrialColumn& column : results::trialColumns()) {
    const auto value = column.value;
    trial.def_property_readonly(
        std::string(column.property).c_str(),
        [value](const TrialRecord& t) {
          return std::visit([](const auto& v) { return py::cast(v); }, value(t));
        },
        std::string(column.doc).c_str());
  }
  trial
      .def_property_readonly(
          "success", [](const TrialRecord& t) { return results::isSuccess(t.outcome); },
          "True for the outcomes the paper counts as success (stable, slipped).")
      .def_property_readonly(
          "conditions", [](const TrialRecord& t) { return conditionsOf(t.conditions); },
          "The scene's conditions (texture, kind, arrangement, object_ids, pose) or None.")
      .def("__repr__", &trialRepr);

  py::class_<results::RunResults>(m, "Results", R"doc(
A result folder as the analyses read it (results::readResults): trials in canonical order
(scene, method, rank), the scenes and methods of the run, rejected grasp counts and the run's
input files. Iterating or indexing goes over the trials.
)doc")
      .def_readonly("trials", &results::RunResults::trials, "list[TrialResult].")
      .def_property_readonly(
          "scenes",
          [](const results::RunResults& r) {
            std::vector<std::string> ids;
            for (const auto& s : r.scenes) ids.push_back(s.id);
            return ids;
          },
          "The run's scene ids (with or without grasps), in database order.")
      .def_readonly("methods", &results::RunResults::methods, "The methods, in order first seen.")
      .def_property_readonly(
          "rejected",
          [](const results::RunResults& r) {
            py::dict d;
            for (const auto& [method, n] : r.rejected) d[py::str(method)] = n;
            return d;
          },
          "Grasps rejected before simulation, per method (dict).")
      .def_property_readonly(
          "sources",
          [](const results::RunResults& r) {
            py::dict d;
            d["database"] = r.sources.database.string();
            d["database_hash"] = r.sources.databaseHash;
            std::vector<std::string> grasps;
            for (const auto& g : r.sources.grasps) grasps.push_back(g.string());
            d["grasps"] = grasps;
            d["hand"] = r.sources.hand.string();
            d["engine"] = r.sources.engine.empty() ? std::string("ode") : r.sources.engine;
            d["engine_settings"] = r.sources.engineSettings;
            d["protocol"] = r.sources.protocol.empty() ? std::string("lift") : r.sources.protocol;
            d["protocol_hash"] = r.sources.protocolHash;
            d["protocol_file"] = r.sources.protocolFile.string();
            return d;
          },
          "The run's inputs (run.csv): database, database_hash (its index's hash; empty for "
          "runs older than the record), grasps, hand, engine (\"ode\" for runs older than the "
          "record) and engine_settings, protocol (\"lift\" when run.csv has no protocol record) "
          "and protocol_hash and protocol_file (the file the run was given; both empty for the "
          "lift).")
      .def_readonly("label", &results::RunResults::label, "The folder's name.")
      .def_readonly("finished", &results::RunResults::finished,
                    "False when the run has not finished (its folder holds unfinished.txt: "
                    "stopped, killed or failed, or still running): its trials are part of it.")
      .def("__len__", [](const results::RunResults& r) { return r.trials.size(); })
      .def(
          "__iter__",
          [](const results::RunResults& r) {
            return py::make_iterator(r.trials.begin(), r.trials.end());
          },
          py::keep_alive<0, 1>())
      .def("__getitem__",
           [](const results::RunResults& r, py::ssize_t i) {
             const auto n = static_cast<py::ssize_t>(r.trials.size());
             if (i < 0) i += n;
             if (i < 0 || i >= n) throw py::index_error("trial index out of range");
             return r.trials[static_cast<std::size_t>(i)];
           })
      .def("__repr__", [](const results::RunResults& r) {
        return "visgrab.Results(" + quoted(r.label) + ", " + std::to_string(r.trials.size()) +
               " trials, " + std::to_string(r.scenes.size()) + " scenes, " +
               std::to_string(r.methods.size()) + " methods)";
      });

  m.def(
      "_read_results",
      [](const fs::path& dir) {
        std::vector<std::string> warnings;
        results::RunResults run = readResults(dir, warnings);
        return py::make_tuple(std::move(run), warnings);
      },
      py::arg("dir"), "read_results's C++ side: (Results, warnings).");

  m.def("_grasp_problems", &graspProblems, py::arg("db"), py::arg("hand"), py::arg("file"),
        "The grasps of a grasp list that a run would reject, as it reports them.");

  m.def("_run", &runBenchmark, py::arg("database"), py::arg("grasps"), py::arg("out"),
        py::arg("hand"), py::arg("scenes"), py::arg("threads"), py::arg("resume"),
        py::arg("engine"), py::arg("progress"), py::arg("repeats"), py::arg("noise"),
        py::arg("seed"), py::arg("adaptive"), py::arg("protocol"),
        "run's C++ side: runner::runBenchmark; returns its summary.");
  m.def("engines", &rwsim::engines::availableEngines,
        "The physics engines this build has: [\"ode\"], and \"mujoco\" when it was built with "
        "MuJoCo.");

  m.def(
      "_analyze",
      [](const std::vector<fs::path>& dirs, const fs::path& out, int threads, bool pictures,
         double ciLevel, int bootstrap, std::optional<std::uint64_t> seed, bool allowUnfinished) {
        if (threads < 1) {
          throw py::value_error("threads must be >= 1, got " + std::to_string(threads));
        }
        analysis::AnalysisOptions analysisOptions;
        analysisOptions.ciLevel = ciLevel;
        analysisOptions.bootstrapResamples = bootstrap;
        if (seed) analysisOptions.bootstrapSeed = *seed;
        analysisOptions.threads = threads;
        // The one check of `visgrab analyze`, in the Python argument's name.
        if (const auto problem = analysis::checkOptions(analysisOptions)) {
          throw py::value_error(
              (problem->pythonArgument.empty() ? problem->field : problem->pythonArgument) + " " +
              problem->problem);
        }
        std::vector<rw::common::Diagnostic> found;
        std::vector<results::RunResults> runs;
        {
          py::gil_scoped_release release;
          runs = results::readResultFolders(dirs, &found);
        }
        for (std::size_t i = 0; i < runs.size() && !allowUnfinished; ++i) {
          try {
            results::requireFinished(runs[i], dirs[i], "allow_unfinished=True");
          } catch (const std::runtime_error& e) {
            throw py::value_error(e.what());
          }
        }
        std::vector<std::string> warnings;
        for (const auto& w : found) warnings.push_back(w.format());
        view::ReportPictureOptions options;
        options.threads = threads;
        // Its protocols/: the protocol of a run other than the lift's (visgrab.data_folder()).
        options.data = py::module_::import("visgrab").attr("data_folder")().cast<fs::path>();
        py::gil_scoped_release release;
        analysis::writeReport(
            runs, out, analysisOptions,
            pictures ? view::showcaseDrawer(options) : analysis::ShowcaseDrawer());
        return warnings;
      },
      py::arg("dirs"), py::arg("out"), py::arg("threads"), py::arg("pictures"), py::arg("ci_level"),
      py::arg("bootstrap"), py::arg("seed"), py::arg("allow_unfinished"),
      "analyze's C++ side: analysis::writeReport as `visgrab analyze`; returns the warnings.");
}

}  // namespace visgrab::python
