#include "visgrab/results/results_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <span>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <variant>

#include "rw/common/write_error.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/trial_columns.hpp"

namespace visgrab::results {

namespace fs = std::filesystem;
using rw::common::Diagnostic;
using rw::common::LoadError;

namespace {

// Version 3 (before closing_capped; version 2 has the same columns): closing_capped is read from
// the detail text, where the trial noted it.
constexpr std::string_view kTrialsColumnsVersion3 =
    "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,simulated_time,"
    "detail";
// Version 1 (before q_gws_unit): its q_gws was computed with unit normal forces.
constexpr std::string_view kTrialsColumnsVersion1 =
    "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,object,simulated_time,detail";
constexpr std::string_view kRunColumns = "record,id,texture,kind,arrangement,objects,pose,count";
constexpr std::size_t kRunFieldCount = 8;

[[noreturn]] void fail(const std::string& file, int line, const std::string& message) {
  Diagnostic d;
  d.file = file;
  d.line = line;
  d.message = message;
  throw LoadError({d});
}

/// One format of a result file: its version, column line and whether it is an older one that
/// starts with a comment line `# visgrab <what> <version>` and escapes with backslashes.
struct Format {
  int version = 0;
  std::string_view columns;
  bool legacy = false;
};

// The current column line, from the per-trial record's table (with the repeat columns of a run
// with repeats when `repeated`).
const std::string& trialsColumns(bool repeated = false) {
  static const std::string line = trialColumnLine(false);
  static const std::string repeatedLine = trialColumnLine(true);
  return repeated ? repeatedLine : line;
}

// The current version with repeats is second: the first is what errors name as expected.
const std::array<Format, 5>& trialsFormats() {
  static const std::array<Format, 5> formats = {{
      {kTrialsFormatVersion, trialsColumns(), false},
      {kTrialsFormatVersion, trialsColumns(true), false},
      {3, kTrialsColumnsVersion3, false},
      {2, kTrialsColumnsVersion3, true},
      {1, kTrialsColumnsVersion1, true},
  }};
  return formats;
}
constexpr std::array<Format, 2> kRunFormats = {{
    {kRunFormatVersion, kRunColumns, false},
    {1, kRunColumns, true},
}};

std::string legacyHeader(std::string_view what, const Format& format) {
  return "# visgrab " + std::string(what) + " " + std::to_string(format.version) + "\n" +
         std::string(format.columns) + "\n";
}

/// The records after the column line, whatever the format.
struct Body {
  std::vector<CsvRecord> records;
  /// The text ends in a record (or line) without its line break: dropped.
  bool torn = false;
  int tornLine = 0;
  /// Bytes up to the end of the last complete record (0: not even the column line).
  std::size_t completeBytes = 0;
  /// The format found; nullptr when the column line is not complete.
  const Format* format = nullptr;
};

/// Older files: one record per line, backslash escapes, the comment line first.
void readLegacyBody(std::string_view text, const Format& format, const std::string& file,
                    Body& body) {
  std::size_t start = 0;
  int lineNo = 0;
  while (start < text.size()) {
    ++lineNo;
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      body.torn = true;
      body.tornLine = lineNo;
      break;
    }
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    start = end + 1;
    body.completeBytes = start;
    if (lineNo == 1) continue;
    if (lineNo == 2) {
      if (line != format.columns) {
        fail(file, 2, "expected the column line '" + std::string(format.columns) + "'");
      }
      continue;
    }
    CsvRecord record;
    record.line = lineNo;
    record.blank = line.empty();
    if (!record.blank) {
      try {
        record.fields = splitLegacyCsvLine(line);
      } catch (const std::invalid_argument& e) {
        fail(file, lineNo, e.what());
      }
    }
    body.records.push_back(std::move(record));
  }
  if (lineNo - (body.torn ? 1 : 0) < 2) {
    fail(file, 2, "expected the column line '" + std::string(format.columns) + "'");
  }
}

/// Reads a result file of one of `formats` (the current one first). A text that is only the
/// beginning of a column line (or of an older file's two header lines) gives no format.
template <std::size_t N>
Body readBody(std::string_view text, std::string_view what, const std::array<Format, N>& formats,
              const std::string& file) {
  Body body;
  const Format& current = formats[0];
  const std::string currentHeader = std::string(current.columns) + "\n";
  const std::string prefix = "# visgrab " + std::string(what) + " ";
  const std::size_t firstBreak = text.find('\n');
  std::string_view first = text.substr(0, firstBreak);
  if (!first.empty() && first.back() == '\r') first.remove_suffix(1);
  if (text.starts_with("#")) {
    // An older format: its comment line names the version.
    const std::size_t secondBreak =
        firstBreak == std::string_view::npos ? firstBreak : text.find('\n', firstBreak + 1);
    if (secondBreak == std::string_view::npos) {
      for (const Format& f : formats) {
        if (f.legacy && legacyHeader(what, f).starts_with(text)) {
          body.torn = true;
          body.tornLine = 1;
          return body;
        }
      }
    }
    if (!first.starts_with(prefix)) {
      fail(file, 1,
           "expected the column line '" + std::string(current.columns) + "', found '" +
               std::string(first) + "'");
    }
    for (const Format& f : formats) {
      if (f.legacy && first == prefix + std::to_string(f.version)) {
        body.format = &f;
        readLegacyBody(text, f, file, body);
        return body;
      }
    }
    std::string older;
    for (const Format& f : formats) {
      if (f.legacy)
        older += (older.empty() ? "'" : " or '") + prefix + std::to_string(f.version) + "'";
    }
    fail(file, 1,
         "format version '" + std::string(first.substr(prefix.size())) +
             "' is not supported (expected the column line '" + std::string(current.columns) +
             "' of version " + std::to_string(current.version) + ", or " + older +
             " of an older version)");
  }
  if (firstBreak == std::string_view::npos) {
    if (!currentHeader.starts_with(text)) {
      fail(file, 1, "expected the column line '" + std::string(current.columns) + "'");
    }
    body.torn = !text.empty();
    body.tornLine = body.torn ? 1 : 0;
    return body;
  }
  const Format* format = nullptr;
  for (const Format& f : formats) {
    if (!f.legacy && first == f.columns) format = &f;
  }
  if (!format) {
    fail(file, 1,
         "expected the column line '" + std::string(current.columns) + "', found '" +
             std::string(first) + "'");
  }
  CsvText csv;
  try {
    csv = parseCsv(text);
  } catch (const CsvSyntaxError& e) {
    fail(file, e.recordLine(), e.what());
  }
  body.format = format;
  body.torn = csv.torn;
  body.tornLine = csv.tornLine;
  body.completeBytes = csv.completeBytes;
  body.records.assign(std::make_move_iterator(csv.records.begin() + 1),
                      std::make_move_iterator(csv.records.end()));
  return body;
}

std::string joinObjects(const std::vector<int>& objects) {
  std::string text;
  for (const int id : objects) {
    if (!text.empty()) text += ' ';
    text += std::to_string(id);
  }
  return text;
}

database::SceneConditions parseConditions(const std::vector<std::string>& f,
                                          const std::string& file, int line) {
  const auto texture = database::textureFromString(f[2]);
  const auto kind = database::sceneKindFromString(f[3]);
  const auto arrangement = database::arrangementFromString(f[4]);
  if (!texture) fail(file, line, "unknown texture '" + f[2] + "' (expected plain or textured)");
  if (!kind) fail(file, line, "unknown scene kind '" + f[3] + "' (expected single or double)");
  if (!arrangement) {
    fail(file, line, "unknown arrangement '" + f[4] + "' (expected standing, lying, apart, close)");
  }
  database::SceneConditions c;
  c.texture = *texture;
  c.kind = *kind;
  std::istringstream objects(f[5]);
  std::string token;
  try {
    while (objects >> token) c.objects.push_back(parseInt(token));
    c.pose = parseInt(f[6]);
  } catch (const std::invalid_argument& e) {
    fail(file, line, e.what());
  }
  const std::string why = database::validate(c);
  if (!why.empty()) fail(file, line, "invalid scene conditions: " + why);
  if (c.arrangement() != *arrangement) {
    fail(file, line,
         "arrangement '" + f[4] + "' does not match pose " + f[6] + " (expected '" +
             std::string(database::toString(c.arrangement())) + "')");
  }
  return c;
}

std::optional<database::SceneConditions> conditionsFromId(const std::string& id) {
  if (auto c = database::parseSceneId(id)) return c;
  return database::parseOriginalId(id);
}

/// Position of a database scene id in database order; past every database scene otherwise.
int databaseOrder(const std::string& id) {
  const auto c = database::parseSceneId(id);
  return c ? database::sceneIndex(*c) : database::kSceneCount;
}

// A result folder's name: its path's last part (a trailing separator dropped).
std::string folderName(const fs::path& dir) {
  fs::path name = dir;
  if (!name.has_filename()) name = name.parent_path();
  return name.filename().string();
}

std::string readWholeFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path.string(), 0, "cannot open the file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

std::string trialsHeader(bool repeated) { return trialsColumns(repeated) + "\n"; }

std::string formatTrialLine(const TrialRecord& t, bool repeated) {
  std::string line;
  for (const TrialColumn& column : trialColumns()) {
    if (column.repeatedOnly && !repeated) continue;
    if (!line.empty()) line += ',';
    line += column.format(t);
  }
  line += '\n';
  return line;
}

std::string formatRunFile(const RunResults& run) {
  std::string text = std::string(kRunColumns) + "\n";
  for (const RunScene& scene : run.scenes) {
    text += "scene," + csvField(scene.id);
    if (scene.conditions) {
      const auto& c = *scene.conditions;
      text += ',' + std::string(database::toString(c.texture)) + ',' +
              std::string(database::toString(c.kind)) + ',' +
              std::string(database::toString(c.arrangement())) + ',' + joinObjects(c.objects) +
              ',' + std::to_string(c.pose) + ",\n";
    } else {
      text += ",,,,,,\n";
    }
  }
  for (const std::string& method : run.methods) text += "method," + csvField(method) + ",,,,,,\n";
  for (const auto& [method, count] : run.rejected) {
    text += "rejected," + csvField(method) + ",,,,,," + std::to_string(count) + "\n";
  }
  if (!run.sources.database.empty()) {
    text += "database," + csvField(run.sources.database.string()) + ",,,,,,\n";
  }
  if (!run.sources.databaseHash.empty()) {
    text += "database_hash," + csvField(run.sources.databaseHash) + ",,,,,,\n";
  }
  for (const auto& file : run.sources.grasps) {
    text += "grasps," + csvField(file.string()) + ",,,,,,\n";
  }
  if (!run.sources.hand.empty()) text += "hand," + csvField(run.sources.hand.string()) + ",,,,,,\n";
  if (!run.sources.engine.empty()) text += "engine," + csvField(run.sources.engine) + ",,,,,,\n";
  if (!run.sources.engineSettings.empty()) {
    text += "engine_settings," + csvField(run.sources.engineSettings) + ",,,,,,\n";
  }
  if (!run.sources.protocol.empty()) {
    text += "protocol," + csvField(run.sources.protocol) + ",,,,,,\n";
    text += "protocol_hash," + csvField(run.sources.protocolHash) + ",,,,,,\n";
  }
  if (!run.sources.protocolFile.empty()) {
    text += "protocol_file," + csvField(run.sources.protocolFile.string()) + ",,,,,,\n";
  }
  if (run.repeats.repeated()) {
    text += "repeats," + std::to_string(run.repeats.count) + ",,,,,,\n";
    text += "noise," + csvField(run.repeats.noise) + ",,,,,,\n";
    if (!run.repeats.adaptive.empty()) {
      text += "adaptive," + csvField(run.repeats.adaptive) + ",,,,,,\n";
    }
  }
  return text;
}

TrialsFile parseTrials(std::string_view text, const std::string& file) {
  TrialsFile out;
  Body body = readBody(text, "trials", trialsFormats(), file);
  out.tornLastLine = body.torn;
  out.tornLine = body.tornLine;
  out.completeBytes = body.completeBytes;
  // Not even the column line was written completely (a kill right after creating the file) or
  // the file is empty: nothing to read; the writer starts the file afresh.
  if (!body.format) return out;
  out.version = body.format->version;
  out.repeated = body.format->columns == trialsColumns(true);
  std::vector<const TrialColumn*> columns;
  for (const TrialColumn& c : trialColumns()) {
    if (!c.repeatedOnly || out.repeated) columns.push_back(&c);
  }
  // Older versions lack columns: q_gws_unit (version 1) and closing_capped (before 4).
  const std::size_t missing = (out.version < 4 ? 1 : 0) + (out.version == 1 ? 1 : 0);
  const std::size_t fieldCount = columns.size() - missing;
  const std::string_view columnLine = body.format->columns;
  std::map<std::tuple<std::string, std::string, std::string, int>, int> seen;
  for (CsvRecord& record : body.records) {
    const int lineNo = record.line;
    if (record.blank) fail(file, lineNo, "empty line (expected a trial)");
    std::vector<std::string> f = std::move(record.fields);
    if (f.size() != fieldCount) {
      fail(file, lineNo,
           std::to_string(f.size()) + " fields, expected " + std::to_string(fieldCount) + " (" +
               std::string(columnLine) + ")");
    }
    // Bring an older record into the current column order.
    if (out.version == 1) f.insert(f.begin() + 8, std::string());
    if (out.version < 4) {
      f.insert(f.end() - 1, rwsim::trial::closingHitCap(f.back()) ? "1" : "0");
    }
    TrialRecord t;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      try {
        columns[i]->parse(f[i], t);
      } catch (const std::invalid_argument& e) {
        fail(file, lineNo, e.what());
      }
      // A number is finite; NaN is only written as an empty q_gws or q_gws_unit ("not computed").
      const TrialValue value = columns[i]->value(t);
      if (const double* number = std::get_if<double>(&value);
          number && !std::isfinite(*number) && !f[i].empty()) {
        fail(file, lineNo,
             "column " + std::string(columns[i]->name) + ": '" + f[i] + "' is not a finite number");
      }
    }
    if (out.version == 1) {
      // Its q_gws was the unit-force epsilon; the paper's Q_GWS was not computed.
      t.qGwsUnit = t.qGws;
      t.qGws = std::numeric_limits<double>::quiet_NaN();
    }
    const auto [it, inserted] =
        seen.emplace(std::make_tuple(t.sceneId, t.method, t.graspId, t.repeat), lineNo);
    if (!inserted) {
      fail(file, lineNo,
           "trial (" + t.sceneId + ", " + t.method + ", " + t.graspId +
               (out.repeated ? ", repeat " + std::to_string(t.repeat) : std::string()) +
               ") is given twice (first at line " + std::to_string(it->second) + ")");
    }
    out.trials.push_back(std::move(t));
    out.lines.push_back(lineNo);
  }
  return out;
}

RunResults parseRunFile(std::string_view text, const std::string& file) {
  RunResults run;
  Body body = readBody(text, "run", kRunFormats, file);
  if (!body.format && !body.torn) {
    fail(file, 1, "missing the column line '" + std::string(kRunColumns) + "'");
  }
  if (body.torn) {
    fail(file, body.tornLine, "the last record has no line break (the file was cut off)");
  }
  std::map<std::string, int> seenScenes;
  std::map<std::string, int> seenMethods;
  int repeatDetailLine = 0;
  for (CsvRecord& record : body.records) {
    const int lineNo = record.line;
    if (record.blank) fail(file, lineNo, "empty line (expected a record)");
    std::vector<std::string> f = std::move(record.fields);
    if (f.size() != kRunFieldCount) {
      fail(file, lineNo,
           std::to_string(f.size()) + " fields, expected " + std::to_string(kRunFieldCount) + " (" +
               std::string(kRunColumns) + ")");
    }
    if (f[1].empty()) fail(file, lineNo, "empty id");
    if (f[0] == "scene") {
      RunScene scene;
      scene.id = f[1];
      const bool known =
          !f[2].empty() || !f[3].empty() || !f[4].empty() || !f[5].empty() || !f[6].empty();
      if (known) scene.conditions = parseConditions(f, file, lineNo);
      const auto [it, inserted] = seenScenes.emplace(scene.id, lineNo);
      if (!inserted) {
        fail(file, lineNo,
             "scene '" + scene.id + "' is given twice (first at line " +
                 std::to_string(it->second) + ")");
      }
      run.scenes.push_back(std::move(scene));
    } else if (f[0] == "method") {
      const auto [it, inserted] = seenMethods.emplace(f[1], lineNo);
      if (!inserted) {
        fail(file, lineNo,
             "method '" + f[1] + "' is given twice (first at line " + std::to_string(it->second) +
                 ")");
      }
      run.methods.push_back(f[1]);
    } else if (f[0] == "rejected") {
      int count = 0;
      try {
        count = parseInt(f[7]);
      } catch (const std::invalid_argument& e) {
        fail(file, lineNo, e.what());
      }
      if (count < 0) fail(file, lineNo, "negative rejected count " + f[7]);
      run.rejected.emplace_back(f[1], count);
    } else if (f[0] == "database") {
      run.sources.database = f[1];
    } else if (f[0] == "database_hash") {
      run.sources.databaseHash = f[1];
    } else if (f[0] == "grasps") {
      run.sources.grasps.emplace_back(f[1]);
    } else if (f[0] == "hand") {
      run.sources.hand = f[1];
    } else if (f[0] == "engine") {
      run.sources.engine = f[1];
    } else if (f[0] == "engine_settings") {
      run.sources.engineSettings = f[1];
    } else if (f[0] == "protocol") {
      run.sources.protocol = f[1];
    } else if (f[0] == "protocol_hash") {
      run.sources.protocolHash = f[1];
    } else if (f[0] == "protocol_file") {
      run.sources.protocolFile = f[1];
    } else if (f[0] == "repeats") {
      try {
        run.repeats.count = parseInt(f[1]);
      } catch (const std::invalid_argument& e) {
        fail(file, lineNo, e.what());
      }
      if (run.repeats.count < 2) {
        fail(file, lineNo, "repeats " + f[1] + " (a repeats record holds 2 or more)");
      }
    } else if (f[0] == "noise") {
      run.repeats.noise = f[1];
      repeatDetailLine = lineNo;
    } else if (f[0] == "adaptive") {
      run.repeats.adaptive = f[1];
      repeatDetailLine = lineNo;
    } else {
      fail(file, lineNo,
           "unknown record '" + f[0] +
               "' (expected scene, method, rejected, database, database_hash, grasps, hand, "
               "engine, engine_settings, protocol, protocol_hash, protocol_file, repeats, noise or "
               "adaptive)");
    }
  }
  if (!run.repeats.repeated() && (!run.repeats.noise.empty() || !run.repeats.adaptive.empty())) {
    fail(file, repeatDetailLine, "a noise or adaptive record without a repeats record");
  }
  return run;
}

void sortTrials(std::vector<TrialRecord>& trials, const std::vector<RunScene>& scenes,
                const std::vector<std::string>& methods) {
  // Listed scenes by position; unlisted ones after them, database scenes in database order first.
  constexpr std::size_t kUnlisted = std::numeric_limits<std::size_t>::max() / 2;
  std::unordered_map<std::string, std::size_t> scenePos;
  for (std::size_t i = 0; i < scenes.size(); ++i) scenePos.emplace(scenes[i].id, i);
  std::unordered_map<std::string, std::size_t> methodPos;
  for (std::size_t i = 0; i < methods.size(); ++i) methodPos.emplace(methods[i], i);
  auto scenePosition = [&](const std::string& id) -> std::size_t {
    if (const auto it = scenePos.find(id); it != scenePos.end()) return it->second;
    if (const auto c = database::parseSceneId(id)) {
      return kUnlisted + static_cast<std::size_t>(database::sceneIndex(*c));
    }
    return std::numeric_limits<std::size_t>::max();
  };
  auto methodPosition = [&](const std::string& name) {
    const auto it = methodPos.find(name);
    return it == methodPos.end() ? methodPos.size() : it->second;
  };
  std::stable_sort(trials.begin(), trials.end(), [&](const TrialRecord& a, const TrialRecord& b) {
    if (a.sceneId != b.sceneId) {
      const std::size_t pa = scenePosition(a.sceneId);
      const std::size_t pb = scenePosition(b.sceneId);
      return pa != pb ? pa < pb : a.sceneId < b.sceneId;
    }
    if (a.method != b.method) {
      const std::size_t pa = methodPosition(a.method);
      const std::size_t pb = methodPosition(b.method);
      return pa != pb ? pa < pb : a.method < b.method;
    }
    if (a.rank != b.rank) return a.rank < b.rank;
    if (a.graspId != b.graspId) return a.graspId < b.graspId;
    return a.repeat < b.repeat;
  });
}

RunResults readResults(const fs::path& dir, std::vector<Diagnostic>* warnings) {
  const fs::path runPath = dir / kRunFileName;
  const fs::path trialsPath = dir / kTrialsFileName;
  std::error_code error;
  const fs::file_status status = fs::status(dir, error);
  if (!fs::exists(status)) {
    fail(dir.string(), 0, "no such result folder (the folder does not exist)");
  }
  if (!fs::is_directory(status)) {
    fail(dir.string(), 0, "is a file, not a result folder (a folder holding trials.csv)");
  }
  RunResults run;
  const bool haveRun = fs::exists(runPath);
  if (haveRun) run = parseRunFile(readWholeFile(runPath), runPath.string());
  if (!fs::exists(trialsPath)) fail(trialsPath.string(), 0, "no trials file in the result folder");
  const std::string text = readWholeFile(trialsPath);
  TrialsFile trials = parseTrials(text, trialsPath.string());
  if (trials.completeBytes == 0) {
    // The writer starts such a file afresh; a reader has no run to read.
    fail(trialsPath.string(), 1,
         std::string(text.empty() ? "empty file" : "the column line is cut off") +
             " (expected the column line '" + trialsColumns() + "')");
  }
  if (haveRun && trials.repeated != run.repeats.repeated()) {
    fail(trialsPath.string(), 1,
         trials.repeated
             ? "trials with repeat columns, but " + runPath.string() + " records no repeats"
             : "trials without repeat columns, but " + runPath.string() + " records " +
                   std::to_string(run.repeats.count) + " repeats");
  }
  if (!haveRun) {
    for (const TrialRecord& t : trials.trials) {
      run.repeats.count = std::max(run.repeats.count, t.repeat + 1);
    }
  }
  if (trials.tornLastLine && warnings) {
    Diagnostic d;
    d.severity = Diagnostic::Severity::kWarning;
    d.file = trialsPath.string();
    d.line = trials.tornLine;
    d.message = "the last record has no line break (a write cut off by a kill): dropped";
    warnings->push_back(d);
  }
  const std::size_t listedScenes = run.scenes.size();
  std::unordered_map<std::string, std::size_t> sceneIndex;
  for (std::size_t i = 0; i < run.scenes.size(); ++i) sceneIndex.emplace(run.scenes[i].id, i);
  for (std::size_t i = 0; i < trials.trials.size(); ++i) {
    TrialRecord& t = trials.trials[i];
    auto it = sceneIndex.find(t.sceneId);
    if (it == sceneIndex.end()) {
      if (haveRun && warnings) {
        Diagnostic d;
        d.severity = Diagnostic::Severity::kWarning;
        d.file = trialsPath.string();
        d.line = trials.lines[i];
        d.message = "scene '" + t.sceneId + "' is not listed in " + std::string(kRunFileName);
        warnings->push_back(d);
      }
      run.scenes.push_back({t.sceneId, conditionsFromId(t.sceneId)});
      it = sceneIndex.emplace(t.sceneId, run.scenes.size() - 1).first;
    }
    t.conditions = run.scenes[it->second].conditions;
    if (std::find(run.methods.begin(), run.methods.end(), t.method) == run.methods.end()) {
      run.methods.push_back(t.method);
    }
  }
  // Scenes known only from trials.csv: database order, then by id (not the order trials
  // finished in).
  std::stable_sort(run.scenes.begin() + static_cast<std::ptrdiff_t>(listedScenes), run.scenes.end(),
                   [](const RunScene& a, const RunScene& b) {
                     const auto ka = std::make_pair(databaseOrder(a.id), std::cref(a.id));
                     return ka < std::make_pair(databaseOrder(b.id), std::cref(b.id));
                   });
  run.trials = std::move(trials.trials);
  sortTrials(run.trials, run.scenes, run.methods);
  run.label = folderName(dir);
  const fs::path unfinished = dir / kUnfinishedFileName;
  run.finished = !fs::exists(unfinished, error);
  if (!run.finished && warnings) {
    Diagnostic d;
    d.severity = Diagnostic::Severity::kWarning;
    d.file = unfinished.string();
    d.message = "the run has not finished (stopped, killed or failed, or still running): " +
                std::to_string(run.trials.size()) + " trials so far";
    warnings->push_back(d);
  }
  return run;
}

void markUnfinished(const fs::path& dir) {
  database::writeFileAtomically(
      dir / kUnfinishedFileName,
      "This run has not finished: `visgrab run` started it and has not reached its end (it was\n"
      "stopped, killed or failed, or it is still running). trials.csv holds the trials finished "
      "so\n"
      "far. The same command with --resume finishes the run and removes this file. Until then\n"
      "`visgrab analyze` and `visgrab agreement` refuse the folder (--allow-unfinished reads it\n"
      "anyway). docs/report.md, \"Stopping, failures and resuming\".\n");
}

void markFinished(const fs::path& dir) {
  std::error_code error;
  fs::remove(dir / kUnfinishedFileName, error);
  if (error) throw rw::common::WriteError((dir / kUnfinishedFileName).string(), error);
}

void requireFinished(const RunResults& run, const fs::path& dir, std::string_view allow) {
  if (run.finished) return;
  throw std::runtime_error(
      dir.string() + ": the run has not finished (" + std::string(kUnfinishedFileName) +
      " is there: it was stopped, killed or failed, or it is still running), so its " +
      std::to_string(run.trials.size()) +
      " trials are only part of it; `visgrab run` with the same options and --resume finishes "
      "it, " +
      std::string(allow) + " uses the trials it has");
}

std::vector<std::string> distinctLabels(const std::vector<fs::path>& dirs) {
  // Each folder's absolute path, its name last (a trailing separator or "." dropped).
  std::vector<std::vector<std::string>> parts;
  for (const fs::path& dir : dirs) {
    std::vector<std::string>& p = parts.emplace_back();
    for (const fs::path& part : fs::absolute(dir).lexically_normal()) {
      if (!part.empty() && part != "." && part != part.root_path()) {
        p.push_back(part.string());
      }
    }
    if (p.empty()) p.push_back(dir.string());
  }
  // The trailing `n` parts of folder i, joined with '/'.
  auto tail = [&parts](std::size_t i, std::size_t n) {
    const std::vector<std::string>& p = parts[i];
    std::string text;
    for (std::size_t k = p.size() - std::min(n, p.size()); k < p.size(); ++k) {
      text += (text.empty() ? "" : "/") + p[k];
    }
    return text;
  };
  std::vector<std::string> names;
  for (const fs::path& dir : dirs) names.push_back(folderName(dir));
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    // The name (as readResults gives it) when no other folder has it; else the fewest trailing
    // parts that no other folder ends in. Labels of different lengths differ (a part holds no
    // '/'), and of the same length differ by construction, so the labels are distinct.
    if (std::count(names.begin(), names.end(), names[i]) == 1) {
      labels.push_back(names[i]);
      continue;
    }
    std::size_t n = 1;
    auto clashes = [&] {
      for (std::size_t j = 0; j < dirs.size(); ++j) {
        if (j != i && tail(j, n) == tail(i, n)) return true;
      }
      return false;
    };
    while (n < parts[i].size() && clashes()) ++n;
    labels.push_back(tail(i, n));
  }
  return labels;
}

std::vector<RunResults> readResultFolders(const std::vector<fs::path>& dirs,
                                          std::vector<Diagnostic>* warnings) {
  std::vector<RunResults> runs;
  runs.reserve(dirs.size());
  for (const fs::path& dir : dirs) runs.push_back(readResults(dir, warnings));
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      std::error_code error;
      if (fs::equivalent(dirs[i], dirs[j], error)) {
        throw std::invalid_argument("result folder " + dirs[j].string() + " is given twice (" +
                                    (dirs[i] == dirs[j] ? "as result " + std::to_string(j + 1) +
                                                              " and " + std::to_string(i + 1)
                                                        : "also as " + dirs[i].string()) +
                                    "): a run compared with itself");
      }
    }
  }
  const std::vector<std::string> labels = distinctLabels(dirs);
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i].label = labels[i];
  return runs;
}

void writeResults(const fs::path& dir, const RunResults& run) {
  std::vector<TrialRecord> trials = run.trials;
  sortTrials(trials, run.scenes, run.methods);
  const bool repeated = run.repeats.repeated();
  std::string text = trialsHeader(repeated);
  for (const TrialRecord& t : trials) text += formatTrialLine(t, repeated);
  database::writeFileAtomically(dir / kRunFileName, formatRunFile(run));
  database::writeFileAtomically(dir / kTrialsFileName, text);
}

}  // namespace visgrab::results
