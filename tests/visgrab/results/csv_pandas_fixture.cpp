// Writes every kind of result CSV the project writes, with the project's own writers, into the
// folder given as the only argument, and truth.json beside them: for each file its column names
// and rows. For trials.csv, run.csv and stages.csv the rows are the values this program put in
// (numbers as JSON numbers, NaN as null); for the report's tables, whose cells the analysis
// computes, they are the file's records as the C++ reader (results::parseCsv) gives them back.
// csv_pandas_test.py reads each file with pandas.read_csv(path) and no options and compares.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "stage_times.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/results_file.hpp"
#include "visgrab/results/results_writer.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::results::RunResults;
using visgrab::results::TrialRecord;

/// A JSON value as text.
using Json = std::string;

Json jsonString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", u);
      out += escaped;
    } else {
      out += c;  // UTF-8 passes as it is
    }
  }
  return out + "\"";
}

Json jsonNumber(double value) {
  return std::isnan(value) ? Json("null") : visgrab::results::formatDouble(value);
}

Json jsonArray(const std::vector<Json>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out + "]";
}

struct Table {
  std::string file;
  std::vector<std::string> columns;
  std::vector<std::vector<Json>> rows;
};

std::vector<Json> strings(const std::vector<std::string>& texts) {
  std::vector<Json> out;
  for (const auto& t : texts) out.push_back(jsonString(t));
  return out;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A file as the C++ reader gives it back (the first record names the columns).
Table parsedTable(const fs::path& dir, const std::string& file) {
  const auto csv = visgrab::results::parseCsv(readText(dir / file));
  if (csv.torn || csv.records.empty()) throw std::runtime_error(file + " is empty or torn");
  Table table{file, csv.records[0].fields, {}};
  for (std::size_t i = 1; i < csv.records.size(); ++i) {
    table.rows.push_back(strings(csv.records[i].fields));
  }
  return table;
}

// Text that needs every rule of RFC 4180 (and some that needs none).
const std::vector<std::string> kDetails = {
    "",         "a,b",    "say \"hi\"", "x\ny", "cr\rz", "crlf\r\nq",      "back\\slash \\n",
    " lead",    "trail ", "\"",         "\n",   ",",     "ünïcødé ✓ 日本", "tab\tthere",
    "a \"\" b", "end\\"};

RunResults makeRun() {
  using visgrab::database::SceneConditions;
  using visgrab::database::Texture;
  RunResults run;
  const SceneConditions a = SceneConditions::single(Texture::kTextured, 5, 1);
  const SceneConditions b = SceneConditions::pairScene(Texture::kPlain, 'e', 6);
  run.scenes = {{visgrab::database::sceneIdOf(a), a},
                {visgrab::database::sceneIdOf(b), b},
                {"odd, \"scene\"\nid", std::nullopt}};
  run.methods = {"plain", "m,1 \"q\"\nx", " lead space"};
  run.rejected = {{"m,1 \"q\"\nx", 2}};
  run.sources.database = "/data/my db, \"v2\"";
  run.sources.grasps = {"grasps/a.csv", "grasps/b\nc.csv"};
  run.sources.hand = "sdh";
  const std::vector<std::string> graspIds = {"g,0", "g\"1\"", "g\n2", "gé 3"};
  std::size_t n = 0;
  for (const auto& scene : run.scenes) {
    for (const auto& method : run.methods) {
      for (int rank = 0; rank < 4; ++rank, ++n) {
        TrialRecord t;
        t.sceneId = scene.id;
        t.method = method;
        t.graspId = graspIds[static_cast<std::size_t>(rank)];
        t.rank = rank;
        t.outcome = rwsim::trial::kOutcomeTable[n % rwsim::trial::kOutcomeTable.size()].outcome;
        t.qLift = 0.1 * static_cast<double>(n);
        t.qGws = n % 3 == 0 ? std::nan("") : 1.0 / static_cast<double>(n + 1);
        t.qGwsUnit = n % 4 == 0 ? std::nan("") : 0.25 * static_cast<double>(n);
        t.object = scene.conditions ? scene.conditions->objects[0] : 0;
        t.simulatedTime = 0.5 + 1e-3 * static_cast<double>(n);
        t.closingCapped = n % 5 == 2;
        t.detail = kDetails[n % kDetails.size()];
        run.trials.push_back(t);
      }
    }
  }
  return run;
}

Table trialsTruth(const RunResults& run) {
  Table table{"results/trials.csv",
              {"scene", "method", "grasp", "rank", "outcome", "robwork_code", "q_lift", "q_gws",
               "q_gws_unit", "object", "simulated_time", "closing_capped", "detail"},
              {}};
  // ResultsWriter::finalize writes the canonical order: the run's scenes, methods, then rank.
  std::vector<TrialRecord> sorted = run.trials;
  visgrab::results::sortTrials(sorted, run.scenes, run.methods);
  for (const TrialRecord& t : sorted) {
    table.rows.push_back({jsonString(t.sceneId), jsonString(t.method), jsonString(t.graspId),
                          std::to_string(t.rank), jsonString(rwsim::trial::outcomeName(t.outcome)),
                          std::to_string(rwsim::trial::robworkCode(t.outcome)), jsonNumber(t.qLift),
                          jsonNumber(t.qGws), jsonNumber(t.qGwsUnit), std::to_string(t.object),
                          jsonNumber(t.simulatedTime), std::string(t.closingCapped ? "1" : "0"),
                          jsonString(t.detail)});
  }
  return table;
}

Table runTruth(const RunResults& run) {
  Table table{"results/run.csv",
              {"record", "id", "texture", "kind", "arrangement", "objects", "pose", "count"},
              {}};
  const Json none = "null";
  for (const auto& scene : run.scenes) {
    if (!scene.conditions) {
      table.rows.push_back(
          {jsonString("scene"), jsonString(scene.id), none, none, none, none, none, none});
      continue;
    }
    const auto& c = *scene.conditions;
    std::string objects;
    for (const int o : c.objects) objects += (objects.empty() ? "" : " ") + std::to_string(o);
    table.rows.push_back({jsonString("scene"), jsonString(scene.id),
                          jsonString(visgrab::database::toString(c.texture)),
                          jsonString(visgrab::database::toString(c.kind)),
                          jsonString(visgrab::database::toString(c.arrangement())),
                          jsonString(objects), std::to_string(c.pose), none});
  }
  for (const auto& m : run.methods) {
    table.rows.push_back({jsonString("method"), jsonString(m), none, none, none, none, none, none});
  }
  for (const auto& [m, count] : run.rejected) {
    table.rows.push_back({jsonString("rejected"), jsonString(m), none, none, none, none, none,
                          std::to_string(count)});
  }
  auto source = [&](const char* record, const fs::path& path) {
    table.rows.push_back(
        {jsonString(record), jsonString(path.string()), none, none, none, none, none, none});
  };
  source("database", run.sources.database);
  for (const auto& g : run.sources.grasps) source("grasps", g);
  source("hand", run.sources.hand);
  return table;
}

/// stages.csv as `visgrab benchmark` writes it, with clocks that step by exact binary fractions.
Table writeStages(const fs::path& dir) {
  double now = 0.0;
  visgrab::app::StageTimes times([&] { return now; }, [&] { return 2.0 * now; });
  const std::vector<std::pair<std::string, std::string>> stages = {
      {"database", "432 scenes, \"generated\""},
      {"trials", "first\nsecond\r\nthird"},
      {"re,port", ""}};
  Table table{"stages.csv", {"stage", "wall_s", "cpu_s", "note"}, {}};
  double total = 0.0;
  for (std::size_t i = 0; i < stages.size(); ++i) {
    const double wall = 1.25 * static_cast<double>(i + 1);
    times.start(stages[i].first);
    now += wall;
    times.stop(stages[i].second);
    total += wall;
    table.rows.push_back({jsonString(stages[i].first), jsonNumber(wall), jsonNumber(2.0 * wall),
                          jsonString(stages[i].second)});
  }
  table.rows.push_back(
      {jsonString("total"), jsonNumber(total), jsonNumber(2.0 * total), jsonString("")});
  std::ofstream(dir / table.file, std::ios::binary) << times.csv();
  return table;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: csv_pandas_fixture DIR\n";
    return 2;
  }
  try {
    const fs::path dir = argv[1];
    std::vector<Table> tables;
    const RunResults run = makeRun();
    {
      visgrab::results::ResultsWriter writer(dir / "results");
      writer.writeRun(run);
      for (const TrialRecord& t : run.trials) writer.append(t);
      writer.finalize();
    }
    tables.push_back(trialsTruth(run));
    tables.push_back(runTruth(run));
    // The report of that run, read back as `visgrab analyze` reads it, with a perturbed repeat
    // of every trial added (each flips held and not held), so that the report also has its
    // robust rates.
    RunResults analysed = visgrab::results::readResults(dir / "results");
    const std::size_t unperturbed = analysed.trials.size();
    for (std::size_t i = 0; i < unperturbed; ++i) {
      TrialRecord t = analysed.trials[i];
      t.repeat = 1;
      t.seed = 1000 + i;
      t.outcome = visgrab::results::isSuccess(t.outcome) ? rwsim::trial::GraspOutcome::kDropped
                                                         : rwsim::trial::GraspOutcome::kStable;
      analysed.trials.push_back(t);
    }
    visgrab::analysis::writeReport({analysed}, dir / "report");
    for (const char* file : {"distribution.csv", "quality.csv", "attempts.csv", "first_success.csv",
                             "objects.csv", "success.csv", "comparisons.csv", "robust.csv"}) {
      Table t = parsedTable(dir / "report", file);
      t.file = "report/" + t.file;
      tables.push_back(std::move(t));
    }
    tables.push_back(writeStages(dir));
    std::ofstream json(dir / "truth.json", std::ios::binary);
    json << "{\"files\": [\n";
    for (std::size_t i = 0; i < tables.size(); ++i) {
      std::vector<Json> rows;
      for (const auto& r : tables[i].rows) rows.push_back(jsonArray(r));
      json << (i ? ",\n" : "") << "{\"file\": " << jsonString(tables[i].file)
           << ", \"columns\": " << jsonArray(strings(tables[i].columns))
           << ", \"rows\": " << jsonArray(rows) << "}";
    }
    json << "\n]}\n";
    return json ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "csv_pandas_fixture: " << e.what() << "\n";
    return 1;
  }
}
