#include "visgrab/results/results_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_support.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/results/trial_columns.hpp"

namespace visgrab::results {
namespace {

using database::SceneConditions;
using database::Texture;
using rwsim::trial::GraspOutcome;

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TrialRecord makeTrial(const std::string& scene, const std::string& method, const std::string& id,
                      int rank, GraspOutcome outcome) {
  TrialRecord t;
  t.sceneId = scene;
  t.method = method;
  t.graspId = id;
  t.rank = rank;
  t.outcome = outcome;
  return t;
}

constexpr std::string_view kVersion2Header =
    "# visgrab trials 2\n"
    "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,simulated_time,"
    "detail\n";

constexpr std::string_view kVersion1Header =
    "# visgrab trials 1\n"
    "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,object,simulated_time,detail\n";

RunResults smallRun() {
  RunResults run;
  const SceneConditions a = SceneConditions::single(Texture::kTextured, 5, 3);
  const SceneConditions b = SceneConditions::pairScene(Texture::kPlain, 'e', 6);
  run.scenes = {{database::sceneIdOf(a), a}, {database::sceneIdOf(b), b}, {"my/odd,scene", {}}};
  run.methods = {"s2EGA1", "s3EGA1"};
  run.rejected = {{"s3EGA1", 4}};
  TrialRecord t1 = makeTrial(run.scenes[0].id, "s2EGA1", "g0", 0, GraspOutcome::kStable);
  t1.qLift = 0.1 + 0.2;  // not exactly representable in short decimal: must round-trip exactly
  t1.qGws = 1.0 / 3.0;
  t1.qGwsUnit = 0.1 / 3.0;
  t1.object = 5;
  t1.simulatedTime = 2.5;
  t1.closingCapped = true;
  t1.detail = "line one\nline \"two\", with \\ backslash";
  TrialRecord t2 = makeTrial(run.scenes[1].id, "s3EGA1", "g,7", 1, GraspOutcome::kInCollision);
  t2.detail = "hand.finger1 vs table (RobWork 12)";
  TrialRecord t3 = makeTrial(run.scenes[2].id, "s2EGA1", "x", 0, GraspOutcome::kTimeout);
  run.trials = {t1, t2, t3};
  return run;
}

// Text that needs every rule of RFC 4180, and text that needs none of them.
const std::vector<std::string> kNastyFields = {
    "plain",           "a,b",       "say \"hi\"", "x\ny",   "cr\rz", "crlf\r\nq",
    "back\\slash \\n", "",          " lead",      "trail ", "\"",    "\n",
    "ünïcødé ✓ 日本",  "tab\there", "a\\"};

TEST(CsvTest, NastyFieldsRoundTripAsOneRecord) {
  const std::string text = csvRecord(kNastyFields);
  // RFC 4180: quotes doubled, line breaks literal (the record spans lines), backslashes as is.
  EXPECT_EQ(text.rfind("plain,\"a,b\",\"say \"\"hi\"\"\",\"x\ny\",\"cr\rz\",\"crlf\r\nq\",", 0), 0u)
      << text;
  EXPECT_NE(text.find(",back\\slash \\n,,\" lead\",\"trail \",\"\"\"\""), std::string::npos)
      << text;
  const CsvText csv = parseCsv(text + "next,1\n");
  ASSERT_EQ(csv.records.size(), 2u);
  EXPECT_EQ(csv.records[0].fields, kNastyFields);
  EXPECT_EQ(csv.records[0].line, 1);
  // The first record spans lines 1-4: line feeds in x\ny, crlf\r\nq and \n, then its own.
  EXPECT_EQ(csv.records[1].line, 5);
  EXPECT_EQ(csv.records[1].fields, (std::vector<std::string>{"next", "1"}));
  EXPECT_FALSE(csv.torn);
  EXPECT_EQ(csv.completeBytes, text.size() + 7);
  EXPECT_EQ(csvField("", true), "\"\"");
  EXPECT_EQ(csvField("a\\b"), "a\\b");
}

TEST(CsvTest, CrLfLineBreaksAreAcceptedAndQuotedOnesKept) {
  const CsvText csv = parseCsv("a,b\r\nc,\"d\r\ne\"\r\n\r\n,\r\n");
  ASSERT_EQ(csv.records.size(), 4u);
  EXPECT_EQ(csv.records[0].fields, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(csv.records[1].fields, (std::vector<std::string>{"c", "d\r\ne"}));
  EXPECT_EQ(csv.records[2].line, 4);
  EXPECT_TRUE(csv.records[2].blank);
  EXPECT_EQ(csv.records[3].fields, (std::vector<std::string>{"", ""}));
  EXPECT_FALSE(csv.records[3].blank);
  EXPECT_FALSE(parseCsv("\"\"\n").records[0].blank);
}

TEST(CsvTest, TornLastRecordIsDroppedWhateverItHolds) {
  const std::string done = "a,b\n\"x\ny\",z\n";
  for (const std::string& torn :
       {std::string("c,\"open"), std::string("c,\"line\n"), std::string("c,\"line\nbreak\""),
        std::string("c,mid-fie"), std::string("c,d\r"), std::string("c,\"q\"x"),
        std::string("\"")}) {
    const CsvText csv = parseCsv(done + torn);
    EXPECT_TRUE(csv.torn) << torn;
    EXPECT_EQ(csv.tornLine, 4) << torn;
    EXPECT_EQ(csv.records.size(), 2u) << torn;
    EXPECT_EQ(csv.completeBytes, done.size()) << torn;
  }
  const CsvText whole = parseCsv(done);
  EXPECT_FALSE(whole.torn);
  EXPECT_EQ(whole.tornLine, 0);
  EXPECT_EQ(whole.completeBytes, done.size());
  EXPECT_TRUE(parseCsv("").records.empty());
}

TEST(CsvTest, SyntaxErrorsSayTheRecordLineAndWhereTheErrorIs) {
  auto expectError = [](const std::string& text, int recordLine, const std::string& what) {
    try {
      parseCsv(text);
      FAIL() << "no error for " << text;
    } catch (const CsvSyntaxError& e) {
      EXPECT_EQ(e.recordLine(), recordLine) << text;
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  // The record starts on line 2; its bad character is on line 3, column 3.
  expectError("h\n\"a\nb\"x,c\nnext\n", 2, "line 3, column 3: text after a closing quote");
  expectError("h\nab\"c\n", 2, "column 3: quote inside an unquoted field");
  expectError("h\nab\rc\n", 2, "column 3: carriage return outside quotes");
  expectError("h\nok,\"q\"\nx\"\n", 3, "column 2: quote inside");
}

TEST(CsvTest, SplitCsvLineReadsOneRfc4180Line) {
  EXPECT_EQ(splitCsvLine("a,\"b,c\",\"say \"\"x\"\"\",back\\n,"),
            (std::vector<std::string>{"a", "b,c", "say \"x\"", "back\\n", ""}));
  EXPECT_THROW(splitCsvLine("a,\"open"), std::invalid_argument);
  EXPECT_THROW(splitCsvLine("\"a\"b"), std::invalid_argument);
  try {
    splitCsvLine("ab,\"open");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("column 4: quoted field is not closed"), std::string::npos)
        << e.what();
  }
}

TEST(CsvTest, LegacyLinesUndoBackslashEscapesAndSayTheColumn) {
  EXPECT_EQ(splitLegacyCsvLine("a,\"x\\ny\\r\\\\z\",\"q\"\"\""),
            (std::vector<std::string>{"a", "x\ny\r\\z", "q\""}));
  EXPECT_THROW(splitLegacyCsvLine("a,\"open"), std::invalid_argument);
  try {
    // a b , " x \ : the bad escape starts at the 6th character.
    splitLegacyCsvLine("ab,\"x\\q\"");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("column 6"), std::string::npos) << e.what();
  }
}

TEST(CsvTest, DoublesRoundTripExactly) {
  for (const double v : {0.0, 0.1 + 0.2, 1.0 / 3.0, -2.5e-17, 1e300}) {
    EXPECT_EQ(parseDouble(formatDouble(v)), v);
  }
  EXPECT_TRUE(std::isnan(parseDouble(formatDouble(std::nan("")))));
  EXPECT_THROW(parseDouble("1.5x"), std::invalid_argument);
  EXPECT_THROW(parseInt(""), std::invalid_argument);
}

TEST(ResultsFileTest, RoundTripKeepsEveryField) {
  test::TempDir dir;
  const RunResults run = smallRun();
  writeResults(dir.path(), run);
  const RunResults back = readResults(dir.path());
  ASSERT_EQ(back.scenes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.scenes[i].id, run.scenes[i].id);
    EXPECT_EQ(back.scenes[i].conditions, run.scenes[i].conditions);
  }
  EXPECT_EQ(back.methods, run.methods);
  EXPECT_EQ(back.rejected, run.rejected);
  EXPECT_EQ(back.label, dir.path().filename().string());
  ASSERT_EQ(back.trials.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const TrialRecord& a = run.trials[i];
    const TrialRecord& b = back.trials[i];
    EXPECT_EQ(b.sceneId, a.sceneId);
    EXPECT_EQ(b.method, a.method);
    EXPECT_EQ(b.graspId, a.graspId);
    EXPECT_EQ(b.rank, a.rank);
    EXPECT_EQ(b.outcome, a.outcome);
    EXPECT_EQ(b.qLift, a.qLift);
    EXPECT_EQ(b.qGws, a.qGws);
    EXPECT_EQ(b.qGwsUnit, a.qGwsUnit);
    EXPECT_EQ(b.object, a.object);
    EXPECT_EQ(b.simulatedTime, a.simulatedTime);
    EXPECT_EQ(b.closingCapped, a.closingCapped);
    EXPECT_EQ(b.detail, a.detail);
    EXPECT_EQ(b.conditions, run.scenes[i].conditions);
  }
  // The file itself: the column line first, one record per trial with the RobWork code, the
  // first one's detail spanning two lines (RFC 4180: no backslash escapes).
  const std::string text = readText(dir.path() / "trials.csv");
  EXPECT_EQ(text.rfind("scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,"
                       "object,simulated_time,closing_capped,detail\n",
                       0),
            0u);
  // The first trial's closing was capped: 1 before its detail; the others 0.
  EXPECT_NE(text.find(",5,2.5,1,\"line one"), std::string::npos) << text;
  EXPECT_NE(text.find(",0,0,0,\"hand.finger1"), std::string::npos) << text;
  EXPECT_NE(text.find(",in_collision,2,"), std::string::npos);
  EXPECT_NE(text.find(",\"line one\nline \"\"two\"\", with \\ backslash\"\n"), std::string::npos)
      << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);
  const std::string runText = readText(dir.path() / "run.csv");
  EXPECT_EQ(runText.rfind("record,id,texture,kind,arrangement,objects,pose,count\nscene,", 0), 0u);
  EXPECT_NE(runText.find("\nscene,\"my/odd,scene\",,,,,,\n"), std::string::npos) << runText;
}

TEST(ResultsFileTest, TornLastLineIsDroppedWithAWarning) {
  test::TempDir dir;
  writeResults(dir.path(), smallRun());
  // A kill in the middle of writing the next line: no line break at the end.
  {
    std::ofstream out(dir.path() / "trials.csv", std::ios::app | std::ios::binary);
    out << "textured/single/cocacola/03,s3EGA1,g9,0,stab";
  }
  std::vector<rw::common::Diagnostic> warnings;
  const RunResults back = readResults(dir.path(), &warnings);
  EXPECT_EQ(back.trials.size(), 3u);
  ASSERT_EQ(warnings.size(), 1u);
  // Column line 1, the first trial on lines 2-3 (its detail holds a line break), then 4 and 5.
  EXPECT_EQ(warnings[0].line, 6);
  EXPECT_NE(warnings[0].message.find("dropped"), std::string::npos);
}

TEST(ResultsFileTest, TornLineThatLooksCompleteIsStillDropped) {
  // A line cut inside its last number parses, but it has no line break: it is dropped.
  const std::string text = trialsHeader() + "s,m,g,0,stable,1,0.9,0.5,0.25,5,1.2,\"\"";
  const TrialsFile file = parseTrials(text, "trials.csv");
  EXPECT_TRUE(file.trials.empty());
  EXPECT_TRUE(file.tornLastLine);
  EXPECT_EQ(file.completeBytes, trialsHeader().size());
}

TEST(ResultsFileTest, EveryPrefixOfAFileReadsAsItsCompleteRecords) {
  // A kill can cut the file after any byte: whatever the cut, the complete records are read,
  // the rest is dropped without an error, and appending continues right after them.
  std::string text = trialsHeader();
  std::vector<std::size_t> ends;  // the byte after each record
  for (std::size_t i = 0; i < kNastyFields.size(); ++i) {
    TrialRecord t = makeTrial("s", kNastyFields[i].empty() ? "m" : kNastyFields[i],
                              "g" + std::to_string(i), static_cast<int>(i), GraspOutcome::kStable);
    t.detail = kNastyFields[(i + 3) % kNastyFields.size()];
    text += formatTrialLine(t);
    ends.push_back(text.size());
  }
  for (std::size_t cut = 0; cut <= text.size(); ++cut) {
    const TrialsFile file = parseTrials(text.substr(0, cut), "trials.csv");
    const auto complete =
        static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), cut) - ends.begin());
    ASSERT_EQ(file.trials.size(), complete) << "cut at " << cut;
    const std::size_t expectedBytes =
        complete > 0 ? ends[complete - 1]
                     : (cut >= trialsHeader().size() ? trialsHeader().size() : 0);
    EXPECT_EQ(file.completeBytes, expectedBytes) << "cut at " << cut;
    EXPECT_EQ(file.tornLastLine, cut != expectedBytes && cut != 0) << "cut at " << cut;
    if (complete > 0) {
      EXPECT_EQ(file.trials.back().detail, kNastyFields[(complete + 2) % kNastyFields.size()]);
    }
  }
}

void expectLoadError(const std::string& text, const std::string& where, const std::string& what) {
  try {
    parseTrials(text, "r/trials.csv");
    FAIL() << "no error for " << where;
  } catch (const rw::common::LoadError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(where + ": error: ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

TEST(ResultsFileTest, CorruptLinesGiveFileAndLine) {
  const std::string h = trialsHeader();
  const std::string good = "s,m,g,0,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n";
  // A record spanning lines 3 and 4 (its detail holds a line break) moves the later lines down.
  const std::string twoLines = "s,m,g1,0,stable,1,0.9,0.5,0.25,5,1.2,0,\"a\nb\"\n";
  expectLoadError(h + good + "s,m,g2,0,stable,1,0.9\n" + good, "r/trials.csv:3", "7 fields");
  expectLoadError(h + good + twoLines + "s,m,g2,0,stable,1,\"0.9\n\"\n", "r/trials.csv:5",
                  "7 fields");
  expectLoadError(h + good + twoLines + "s,m,g2,0,wobbly,1,0,0,0,0,0,0,\"\"\n", "r/trials.csv:5",
                  "unknown outcome 'wobbly'");
  expectLoadError(h + good + "s,m,g2,0,stable,3,0,0,0,0,0,0,\"\"\n", "r/trials.csv:3",
                  "RobWork code 3 does not match");
  expectLoadError(h + good + "s,m,g2,zero,stable,1,0,0,0,0,0,0,\"\"\n", "r/trials.csv:3",
                  "'zero' is not an integer");
  // Syntax errors: the line where the record starts, and the error's own line and column.
  expectLoadError(h + good + "s,m,\"g\nx\"y,0,stable,1,0,0,0,0,0,0,\"\"\n" + good, "r/trials.csv:3",
                  "line 4, column 3: text after a closing quote");
  expectLoadError(h + good + "s,m,g\"2,0,stable,1,0,0,0,0,0,0,\"\"\n", "r/trials.csv:3",
                  "column 6: quote inside an unquoted field");
  expectLoadError(h + good + good, "r/trials.csv:3", "given twice (first at line 2)");
  expectLoadError(h + good + twoLines + twoLines, "r/trials.csv:5",
                  "given twice (first at line 3)");
  expectLoadError(h + "\n" + good, "r/trials.csv:2", "empty line");
  expectLoadError("# visgrab trials 7\n" + good, "r/trials.csv:1", "version '7'");
  expectLoadError("scene,method\n" + good, "r/trials.csv:1", "expected the column line");
  expectLoadError("sc\"ene", "r/trials.csv:1", "expected the column line");
  // A version 1 line (11 fields) under the current column line, and the other way round.
  expectLoadError(h + "s,m,g,0,stable,1,0.9,0.5,5,1.2,\"\"\n", "r/trials.csv:2", "11 fields");
  expectLoadError(std::string(kVersion1Header) + good, "r/trials.csv:3", "13 fields, expected 11");
  // Older files keep their rules: a backslash escape it does not know, a line break at the end
  // of a line inside quotes.
  expectLoadError(std::string(kVersion2Header) + "s,m,g,0,stable,1,0,0,0,0,0,\"\\q\"\n",
                  "r/trials.csv:3", "unknown escape");
  expectLoadError(std::string(kVersion2Header) + "s,m,g,0,stable,1,0,0,0,0,0,\"a\nb\"\n",
                  "r/trials.csv:3", "not closed");
  expectLoadError("# visgrab trials 2\nscene,method\n" + good, "r/trials.csv:2",
                  "expected the column line");
}

TEST(ResultsFileTest, EmptyQualityMeansNotComputed) {
  TrialRecord t = makeTrial("s", "m", "g", 0, GraspOutcome::kStable);
  t.qGws = std::nan("");
  t.qGwsUnit = 0.125;
  const std::string line = formatTrialLine(t);
  EXPECT_NE(line.find(",stable,1,0,,0.125,0,"), std::string::npos) << line;
  const TrialsFile back = parseTrials(trialsHeader() + line, "trials.csv");
  ASSERT_EQ(back.trials.size(), 1u);
  EXPECT_TRUE(std::isnan(back.trials[0].qGws));
  EXPECT_EQ(back.trials[0].qGwsUnit, 0.125);
  EXPECT_EQ(back.version, kTrialsFormatVersion);
}

TEST(ResultsFileTest, ColumnLineIsTheRecordTable) {
  // One definition: the header, each record's field count and the Python properties follow
  // trialColumns(); the header written is its names in order, the repeat columns only in a run
  // with repeats.
  std::string names;
  std::string repeatedNames;
  for (const TrialColumn& c : trialColumns()) {
    repeatedNames += std::string(repeatedNames.empty() ? "" : ",") + std::string(c.name);
    if (!c.repeatedOnly) names += std::string(names.empty() ? "" : ",") + std::string(c.name);
  }
  EXPECT_EQ(trialsHeader(), names + "\n");
  EXPECT_EQ(trialsHeader(true), repeatedNames + "\n");
  EXPECT_EQ(trialsHeader(true).rfind("scene,method,grasp,rank,repeat,seed,outcome,", 0), 0u);
  EXPECT_EQ(trialColumns().size(), 15u);
  EXPECT_EQ(trialColumns()[2].property, "id");
  TrialRecord t = makeTrial("s", "m", "g", 0, GraspOutcome::kSlipped);
  t.closingCapped = true;
  t.repeat = 3;
  t.seed = 123456789012345ULL;
  EXPECT_EQ(std::get<long long>(trialColumns()[4].value(t)), 3);
  EXPECT_EQ(std::get<long long>(trialColumns()[5].value(t)), 123456789012345LL);
  EXPECT_EQ(std::get<bool>(trialColumns()[13].value(t)), true);
  EXPECT_EQ(std::get<std::string>(trialColumns()[6].value(t)), "slipped");
  EXPECT_EQ(std::get<long long>(trialColumns()[7].value(t)), 5);
}

TEST(ResultsFileTest, RepeatedRunsRoundTripWithTheirRepeatColumnsAndRecords) {
  test::TempDir dir;
  RunResults run = smallRun();
  run.repeats.count = 3;
  run.repeats.noise = "hand 0.002 m 0.01 rad; seed 1";
  run.repeats.adaptive = "stop after 3 agreeing trials";
  std::vector<TrialRecord> trials;
  for (const TrialRecord& t : run.trials) {
    for (int k = 2; k >= 0; --k) {  // out of order: the writer sorts by repeat last
      TrialRecord r = t;
      r.repeat = k;
      r.seed = k == 0 ? 0 : (9223372036854775807ULL - static_cast<unsigned>(k));
      trials.push_back(r);
    }
  }
  run.trials = trials;
  writeResults(dir.path(), run);
  const RunResults back = readResults(dir.path());
  EXPECT_EQ(back.repeats, run.repeats);
  ASSERT_EQ(back.trials.size(), 9u);
  for (std::size_t i = 0; i < back.trials.size(); ++i) {
    EXPECT_EQ(back.trials[i].repeat, static_cast<int>(i % 3));
    EXPECT_EQ(back.trials[i].seed, i % 3 == 0 ? 0u : 9223372036854775807ULL - i % 3);
  }
  const std::string text = readText(dir.path() / "trials.csv");
  EXPECT_EQ(text.rfind("scene,method,grasp,rank,repeat,seed,outcome,", 0), 0u) << text;
  EXPECT_NE(text.find(",g0,0,1,9223372036854775806,stable,"), std::string::npos) << text;
  const std::string runText = readText(dir.path() / "run.csv");
  EXPECT_NE(runText.find("\nrepeats,3,,,,,,\nnoise,hand 0.002 m 0.01 rad; seed 1,,,,,,\n"
                         "adaptive,stop after 3 agreeing trials,,,,,,\n"),
            std::string::npos)
      << runText;
  // The same trial and repeat twice, a negative repeat, a seed beyond 63 bits.
  const std::string h = trialsHeader(true);
  const std::string line = "s,m,g,0,1,77,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n";
  try {
    parseTrials(h + line + line, "r/trials.csv");
    ADD_FAILURE() << "no error for a repeat given twice";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("r/trials.csv:3: error: trial (s, m, g, repeat 1) is "
                                         "given twice (first at line 2)"),
              std::string::npos)
        << e.what();
  }
  expectLoadError(h + "s,m,g,0,-1,77,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n", "r/trials.csv:2",
                  "negative repeat -1");
  expectLoadError(h + "s,m,g,0,1,9223372036854775808,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n",
                  "r/trials.csv:2", "out of range (63 bits)");
  expectLoadError(h + "s,m,g,0,1,x7,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n", "r/trials.csv:2",
                  "seed 'x7' is not an unsigned integer");
  // A run.csv that says repeats while trials.csv has no repeat columns, and the other way.
  writeResults(dir.path(), smallRun());
  const std::string plainTrials = readText(dir.path() / "trials.csv");
  test::writeFile(dir.path() / "run.csv", runText);
  try {
    readResults(dir.path());
    ADD_FAILURE() << "no error for trials without repeat columns in a repeated run";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("trials without repeat columns, but"), std::string::npos)
        << e.what();
  }
  // A repeats record of 1, and a noise record without repeats.
  for (const auto& [bad, what] : std::vector<std::pair<std::string, std::string>>{
           {"repeats,1,,,,,,\n", "a repeats record holds 2 or more"},
           {"noise,hand,,,,,,\n", "a noise or adaptive record without a repeats record"}}) {
    try {
      parseRunFile("record,id,texture,kind,arrangement,objects,pose,count\n" + bad, "r/run.csv");
      ADD_FAILURE() << "no error for " << bad;
    } catch (const rw::common::LoadError& e) {
      EXPECT_NE(std::string(e.what()).find("r/run.csv:2: error: "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(plainTrials.empty());
}

TEST(ResultsFileTest, Version3FilesReadClosingCappedFromTheDetail) {
  // Version 3: RFC 4180 without closing_capped; the trial noted a capped closing in its detail.
  const std::string header =
      "scene,method,grasp,rank,outcome,robwork_code,q_lift,q_gws,q_gws_unit,object,"
      "simulated_time,detail\n";
  const std::string capped =
      "s,m,g1,0,slipped,5,0.5,0.25,0.125,3,6.5,\"drift [closing hit the cap: 5 s "
      "simulated with f1.Joint2 still at 0.02 rad/s (at rest below 0.01)]\"\n";
  const std::string plain = "s,m,g2,1,dropped,4,0,0,0,3,2,\"object fell\"\n";
  const TrialsFile back = parseTrials(header + capped + plain, "old/trials.csv");
  EXPECT_EQ(back.version, 3);
  ASSERT_EQ(back.trials.size(), 2u);
  EXPECT_TRUE(back.trials[0].closingCapped);
  EXPECT_FALSE(back.trials[1].closingCapped);
  EXPECT_EQ(back.trials[0].qGwsUnit, 0.125);
  EXPECT_EQ(back.trials[0].simulatedTime, 6.5);
  // Written again it is version 4 with the column.
  const std::string again = formatTrialLine(back.trials[0]);
  EXPECT_NE(again.find(",3,6.5,1,\"drift"), std::string::npos) << again;
  // A version 3 record with a version 4 field count is an error naming file and line.
  try {
    parseTrials(header + "s,m,g1,0,slipped,5,0.5,0.25,0.125,3,6.5,1,\"x\"\n", "old/trials.csv");
    ADD_FAILURE() << "expected a LoadError";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("old/trials.csv:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("13 fields, expected 12"), std::string::npos) << e.what();
  }
  // closing_capped must be 0 or 1.
  try {
    parseTrials(trialsHeader() + "s,m,g1,0,slipped,5,0.5,0.25,0.125,3,6.5,yes,\"x\"\n", "t.csv");
    ADD_FAILURE() << "expected a LoadError";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("closing_capped 'yes' is not 0 or 1"), std::string::npos)
        << e.what();
  }
}

TEST(ResultsFileTest, Version1FilesAreReadWithTheirQGwsAsTheUnitColumn) {
  // Before q_gws_unit, q_gws was computed with unit normal forces: it is that column now, and
  // the paper's Q_GWS is unknown (NaN), never silently the unit value.
  const std::string text = std::string(kVersion1Header) +
                           "s,m,g,0,stable,1,0.9,0.0625,5,1.5,\"held\"\n"
                           "s,m,h,1,missed,3,0,0,0,2,\"\"\n";
  const TrialsFile file = parseTrials(text, "trials.csv");
  EXPECT_EQ(file.version, 1);
  ASSERT_EQ(file.trials.size(), 2u);
  const TrialRecord& t = file.trials[0];
  EXPECT_EQ(t.qLift, 0.9);
  EXPECT_EQ(t.qGwsUnit, 0.0625);
  EXPECT_TRUE(std::isnan(t.qGws));
  EXPECT_EQ(t.object, 5);
  EXPECT_EQ(t.simulatedTime, 1.5);
  EXPECT_EQ(t.detail, "held");
  EXPECT_EQ(file.trials[1].qGwsUnit, 0.0);
  EXPECT_EQ(file.completeBytes, text.size());
  // A torn version 1 header starts the file afresh like a torn current one.
  EXPECT_TRUE(parseTrials(std::string(kVersion1Header).substr(0, 30), "t").trials.empty());
}

TEST(ResultsFileTest, Version2FilesAreReadWithTheirBackslashEscapes) {
  const std::string text = std::string(kVersion2Header) +
                           "s,\"m,1\",g,0,stable,1,0.9,,0.25,5,1.5,\"a\\nb \\\\ \"\"c\"\"\\r\"\n"
                           "s,m,h,1,missed,3,0,0,0,0,2,\"\"\n"
                           "s,m,i,2,miss";
  const TrialsFile file = parseTrials(text, "trials.csv");
  EXPECT_EQ(file.version, 2);
  ASSERT_EQ(file.trials.size(), 2u);
  EXPECT_EQ(file.trials[0].method, "m,1");
  EXPECT_EQ(file.trials[0].detail, "a\nb \\ \"c\"\r");
  EXPECT_TRUE(std::isnan(file.trials[0].qGws));
  EXPECT_EQ(file.trials[0].qGwsUnit, 0.25);
  EXPECT_EQ(file.lines, (std::vector<int>{3, 4}));
  EXPECT_TRUE(file.tornLastLine);
  EXPECT_EQ(file.tornLine, 5);
  EXPECT_EQ(file.completeBytes, text.size() - 12);
  // A torn version 2 header starts the file afresh.
  const TrialsFile fresh = parseTrials(std::string(kVersion2Header).substr(0, 40), "t");
  EXPECT_TRUE(fresh.trials.empty());
  EXPECT_EQ(fresh.completeBytes, 0u);
}

TEST(ResultsFileTest, Version1RunFilesAreReadWithTheirBackslashEscapes) {
  const RunResults run = parseRunFile(
      "# visgrab run 1\nrecord,id,texture,kind,arrangement,objects,pose,count\n"
      "scene,plain/single/cocacola/03,plain,single,standing,5,3,\n"
      "scene,\"odd\\nscene\",,,,,,\n"
      "method,\"m,\\\\x\",,,,,,\n"
      "rejected,\"m,\\\\x\",,,,,,3\n",
      "run.csv");
  ASSERT_EQ(run.scenes.size(), 2u);
  EXPECT_EQ(run.scenes[1].id, "odd\nscene");
  EXPECT_FALSE(run.scenes[1].conditions);
  ASSERT_TRUE(run.scenes[0].conditions);
  EXPECT_EQ(run.scenes[0].conditions->pose, 3);
  EXPECT_EQ(run.methods, (std::vector<std::string>{"m,\\x"}));
  EXPECT_EQ(run.rejected, (std::vector<std::pair<std::string, int>>{{"m,\\x", 3}}));
}

TEST(ResultsFileTest, RunFileRecordsMaySpanLines) {
  RunResults run = smallRun();
  run.scenes[2].id = "two\nlines, \"quoted\"";
  run.methods = {"s2EGA1", "s3\r\nEGA1"};
  run.rejected = {{"s3\r\nEGA1", 4}};
  run.sources.database = "/data/my db, v2";
  run.sources.grasps = {"a\nb.csv"};
  run.sources.hand = "sdh";
  run.sources.protocol = "my shake";
  run.sources.protocolHash = "0123456789abcdef";
  run.sources.protocolFile = "/protocols/my,\nshake.xml";
  const std::string text = formatRunFile(run);
  const RunResults back = parseRunFile(text, "run.csv");
  ASSERT_EQ(back.scenes.size(), 3u);
  EXPECT_EQ(back.scenes[2].id, run.scenes[2].id);
  EXPECT_EQ(back.methods, run.methods);
  EXPECT_EQ(back.rejected, run.rejected);
  EXPECT_EQ(back.sources.database, run.sources.database);
  EXPECT_EQ(back.sources.grasps, run.sources.grasps);
  EXPECT_EQ(back.sources.hand, run.sources.hand);
  EXPECT_EQ(back.sources.protocol, run.sources.protocol);
  EXPECT_EQ(back.sources.protocolHash, run.sources.protocolHash);
  EXPECT_EQ(back.sources.protocolFile, run.sources.protocolFile);
  EXPECT_NE(text.find("\nprotocol_file,\"/protocols/my,\nshake.xml\",,,,,,\n"), std::string::npos)
      << text;
  // run.csv is written atomically: a cut-off one is an error, at the line its record starts.
  const std::string cut = text.substr(0, text.find("two\nlines") + 4);
  try {
    parseRunFile(cut, "r/run.csv");
    FAIL();
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("r/run.csv:4: error: the last record has no line break"),
              std::string::npos)
        << e.what();
  }
}

TEST(ResultsFileTest, CorruptRunFileGivesFileAndLine) {
  test::TempDir dir;
  writeResults(dir.path(), smallRun());
  test::writeFile(dir.path() / "run.csv",
                  "# visgrab run 1\nrecord,id,texture,kind,arrangement,objects,pose,count\n"
                  "scene,a,textured,single,standing,5,3,\n"
                  "scene,b,textured,single,standing,5,7,\n");
  try {
    readResults(dir.path());
    FAIL();
  } catch (const rw::common::LoadError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("run.csv:4: error: arrangement 'standing' does not match pose 7"),
              std::string::npos)
        << message;
  }
}

TEST(ResultsFileTest, MissingRunFileDerivesScenesFromIds) {
  test::TempDir dir;
  writeResults(dir.path(), smallRun());
  std::filesystem::remove(dir.path() / "run.csv");
  const RunResults back = readResults(dir.path());
  ASSERT_EQ(back.scenes.size(), 3u);
  // Database scenes first in database order (plain before textured), then the unknown one.
  EXPECT_EQ(back.scenes[0].id, "plain/double/cocacola_saltcylinder/06");
  ASSERT_TRUE(back.scenes[0].conditions);
  EXPECT_EQ(back.scenes[0].conditions->objects, (std::vector<int>{5, 14}));
  EXPECT_EQ(back.scenes[1].id, "textured/single/cocacola/03");
  EXPECT_FALSE(back.scenes[2].conditions);
  EXPECT_EQ(back.trials[0].sceneId, "plain/double/cocacola_saltcylinder/06");
  EXPECT_EQ(back.trials[0].conditions, back.scenes[0].conditions);
}

// The message of the LoadError readResults(dir) throws ("" when it reads).
std::string readError(const std::filesystem::path& dir) {
  try {
    readResults(dir);
  } catch (const rw::common::LoadError& e) {
    return e.what();
  }
  return "";
}

TEST(ResultsFileTest, BadResultFoldersSayWhatIsWrong) {
  test::TempDir dir;
  // A folder that does not exist: said of the folder, not of a trials.csv inside it.
  const std::filesystem::path missing = dir.path() / "nonexist";
  EXPECT_EQ(readError(missing),
            missing.string() + ": error: no such result folder (the folder does not exist)");
  // A file given as the folder.
  const std::filesystem::path file = dir.path() / "base.csv";
  test::writeFile(file, "a,b\n");
  EXPECT_EQ(readError(file), file.string() +
                                 ": error: is a file, not a result folder (a folder holding "
                                 "trials.csv)");
  // A folder without trials.csv.
  std::filesystem::create_directories(dir.path() / "empty");
  EXPECT_EQ(readError(dir.path() / "empty"), (dir.path() / "empty" / "trials.csv").string() +
                                                 ": error: no trials file in the result folder");
}

TEST(ResultsFileTest, TrialsFileWithoutItsColumnLineIsAnErrorAtLine1) {
  test::TempDir dir;
  const std::filesystem::path trials = dir.path() / "trials.csv";
  // 0 bytes: no run to report on (not a report of 0 grasps).
  test::writeFile(trials, "");
  EXPECT_EQ(readError(dir.path()), trials.string() +
                                       ":1: error: empty file (expected the column line '" +
                                       trialColumnLine(false) + "')");
  // Cut off inside the column line.
  test::writeFile(trials, "scene,method,gr");
  EXPECT_EQ(readError(dir.path()), trials.string() +
                                       ":1: error: the column line is cut off (expected the "
                                       "column line '" +
                                       trialColumnLine(false) + "')");
  // The column line alone is a run without trials: read, no error.
  test::writeFile(trials, trialsHeader());
  EXPECT_EQ(readError(dir.path()), "");
  EXPECT_TRUE(readResults(dir.path()).trials.empty());
}

TEST(ResultsFileTest, NumbersThatAreNotFiniteAreErrorsNamingTheColumn) {
  // docs/report.md: numbers are shortest round-trip decimals; only an empty q_gws or q_gws_unit
  // means "not computed". A nan or inf elsewhere would make a mean silently undefined.
  const std::string h = trialsHeader();
  const std::string good = "s,m,g,0,stable,1,0.9,0.5,0.25,5,1.2,0,\"\"\n";
  expectLoadError(h + good + "s,m,g2,0,stable,1,nan,0.5,0.25,5,1.2,0,\"\"\n", "r/trials.csv:3",
                  "column q_lift: 'nan' is not a finite number");
  expectLoadError(h + "s,m,g2,0,stable,1,0.9,inf,0.25,5,1.2,0,\"\"\n", "r/trials.csv:2",
                  "column q_gws: 'inf' is not a finite number");
  expectLoadError(h + "s,m,g2,0,stable,1,0.9,0.5,nan,5,1.2,0,\"\"\n", "r/trials.csv:2",
                  "column q_gws_unit: 'nan' is not a finite number");
  expectLoadError(h + "s,m,g2,0,stable,1,0.9,0.5,0.25,5,-inf,0,\"\"\n", "r/trials.csv:2",
                  "column simulated_time: '-inf' is not a finite number");
  expectLoadError(std::string(kVersion1Header) + "s,m,g,0,stable,1,nan,0.0625,5,1.5,\"\"\n",
                  "r/trials.csv:3", "column q_lift: 'nan' is not a finite number");
  // Empty Q fields stay "not computed".
  const TrialsFile file = parseTrials(h + "s,m,g2,0,stable,1,0.9,,,5,1.2,0,\"\"\n", "t");
  ASSERT_EQ(file.trials.size(), 1u);
  EXPECT_TRUE(std::isnan(file.trials[0].qGws));
  EXPECT_TRUE(std::isnan(file.trials[0].qGwsUnit));
}

TEST(ResultsFileTest, FoldersOfTheSameNameGetLabelsThatTellThemApart) {
  namespace fs = std::filesystem;
  test::TempDir dir;
  // The layout `visgrab benchmark` writes: BENCH/results.
  const fs::path a = dir.path() / "benchA" / "results";
  const fs::path b = dir.path() / "benchB" / "results";
  const fs::path other = dir.path() / "other";
  for (const fs::path& p : {a, b, other}) {
    fs::create_directories(p);
    writeResults(p, smallRun());
  }
  const std::vector<RunResults> runs = readResultFolders({a, b, other});
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].label, "benchA/results");
  EXPECT_EQ(runs[1].label, "benchB/results");
  // A name no other folder has stays the name, as readResults gives it.
  EXPECT_EQ(runs[2].label, "other");
  EXPECT_EQ(readResultFolders({a, other})[0].label, "results");
  EXPECT_EQ(readResultFolders({a})[0].label, "results");
  // docs/python.md's example: "results" and "other/results", the first relative to the working
  // directory: the shortest trailing parts of the absolute paths that differ.
  EXPECT_EQ(distinctLabels({"/w/x/results", "/w/x/other/results"}),
            (std::vector<std::string>{"x/results", "other/results"}));
  // Each label as short as it can be: b/a/r and c/a/r need 3 parts, d/r 2, the unique e 1.
  EXPECT_EQ(distinctLabels({"/b/a/r", "/c/a/r", "/d/r/", "/e"}),
            (std::vector<std::string>{"b/a/r", "c/a/r", "d/r", "e"}));
  // A trailing separator and "." do not count as parts.
  EXPECT_EQ(distinctLabels({"/p/./results/", "/q/results"}),
            (std::vector<std::string>{"p/results", "q/results"}));
}

TEST(ResultsFileTest, OneFolderGivenTwiceIsRefused) {
  namespace fs = std::filesystem;
  test::TempDir dir;
  const fs::path a = dir.path() / "benchA" / "results";
  fs::create_directories(a);
  writeResults(a, smallRun());
  try {
    readResultFolders({a, a});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "result folder " + a.string() +
                                         " is given twice (as result 1 and 2): a run compared "
                                         "with itself");
  }
  // Under another path to it.
  const fs::path again = dir.path() / "benchA" / "." / "results" / "";
  try {
    readResultFolders({a, again});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "result folder " + a.string() + " is given twice (also as " +
                                         again.string() + "): a run compared with itself");
  }
}

}  // namespace
}  // namespace visgrab::results
