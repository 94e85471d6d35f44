// ACRONYM's table example end to end, as a user runs it: `db from-acronym`, `import acronym`,
// `run --hand franka --protocol shake`, `agreement --labels`; the shake protocol's verdicts
// against FleX's labels (docs/validation.md, "Agreement with ACRONYM's labels"). Reads
// ../shared/acronym (its NOTICE: tests only); skipped with the reason when it is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "rw/common/text_file.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::test::RunResult;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

// The fields of label-agreement.csv's row `key` by column name.
std::vector<std::pair<std::string, std::string>> agreementRow(const fs::path& csv,
                                                              const std::string& key) {
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  const auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    std::string f;
    while (std::getline(s, f, ',')) fields.push_back(f);
    return fields;
  };
  const std::vector<std::string> names = split(header);
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<std::string> values = split(line);
    if (values.size() < 2 || values[1] != key) continue;
    std::vector<std::pair<std::string, std::string>> row;
    for (std::size_t i = 0; i < names.size() && i < values.size(); ++i) {
      row.emplace_back(names[i], values[i]);
    }
    return row;
  }
  return {};
}

double field(const std::vector<std::pair<std::string, std::string>>& row, const std::string& n) {
  for (const auto& [name, value] : row) {
    if (name == n) return std::stod(value);
  }
  ADD_FAILURE() << "no column " << n;
  return 0.0;
}

constexpr const char* kAbsent =
    "ACRONYM's example data is absent: set VISGRAB_ACRONYM_DATA to the folder holding grasps/ "
    "and meshes/ (or RW_COMPAT_DATA beside it, as .ci/run does)";

fs::path tableExample(const fs::path& data) {
  return data / "grasps/Table_99cf659ae2fe4b87b72437fd995483b_0.009700376721042367.h5";
}

TEST(AcronymAgreement, ADatabaseFromSeveralFilesHasOneSceneEachInTheirOrder) {
  const auto data = visgrab::test::acronymDataDir();
  if (!data) GTEST_SKIP() << kAbsent;
  const fs::path h5 = tableExample(*data);
  ASSERT_TRUE(fs::is_regular_file(h5)) << h5;
  // The file and a copy named as a second scale of the same mesh: two scenes, the second
  // named with _2 (docs/database-format.md, "Scenes from objects alone").
  visgrab::test::TempDir dir;
  const fs::path copy = dir.path() / "Table_99cf659ae2fe4b87b72437fd995483b_0.02.h5";
  fs::copy_file(h5, copy);
  const fs::path db = dir.path() / "db";
  const RunResult made =
      runVisgrab("db from-acronym " + shellQuoted(h5) + " " + shellQuoted(copy) + " --mesh-root " +
                 shellQuoted(*data) + " --out " + shellQuoted(db) + " --quiet");
  ASSERT_EQ(made.exitCode, 0) << made.output;
  const RunResult listed = runVisgrab("db list --db " + shellQuoted(db));
  ASSERT_EQ(listed.exitCode, 0) << listed.output;
  const std::string first = "plain/single/table_99cf659ae2fe4b87b72437fd995483b/01";
  const std::string second = "plain/single/table_99cf659ae2fe4b87b72437fd995483b_2/01";
  EXPECT_NE(listed.output.find(first), std::string::npos) << listed.output;
  EXPECT_NE(listed.output.find(second), std::string::npos) << listed.output;
  EXPECT_LT(listed.output.find(first), listed.output.find(second)) << listed.output;
  // Each file's grasps find the scene made from it.
  const fs::path grasps = dir.path() / "grasps.csv";
  const RunResult imported = runVisgrab("import acronym " + shellQuoted(copy) + " --db " +
                                        shellQuoted(db) + " --out " + shellQuoted(grasps));
  ASSERT_EQ(imported.exitCode, 0) << imported.output;
  EXPECT_NE(imported.output.find("2000 grasps imported, 0 rejected"), std::string::npos)
      << imported.output;
  const std::string list = rw::common::readTextFileOrThrow(grasps);
  EXPECT_NE(list.find(second), std::string::npos) << list.substr(0, 400);
  EXPECT_EQ(list.find(first + ","), std::string::npos) << list.substr(0, 400);
  // One file twice is one scene asked for twice: refused.
  const RunResult twice =
      runVisgrab("db from-acronym " + shellQuoted(h5) + " " + shellQuoted(h5) + " --mesh-root " +
                 shellQuoted(*data) + " --out " + shellQuoted(dir.path() / "db2") + " --quiet");
  EXPECT_EQ(twice.exitCode, 1) << twice.output;
  EXPECT_NE(twice.output.find(h5.filename().string() + " is given twice"), std::string::npos)
      << twice.output;
}

TEST(AcronymAgreement, ShakeVerdictsAgainstFlexLabelsOnTheTableExample) {
  const auto data = visgrab::test::acronymDataDir();
  if (!data) GTEST_SKIP() << kAbsent;
  const fs::path h5 = tableExample(*data);
  ASSERT_TRUE(fs::is_regular_file(h5)) << h5;
  visgrab::test::TempDir dir;
  const fs::path db = dir.path() / "db";
  const RunResult made = runVisgrab("db from-acronym " + shellQuoted(h5) + " --mesh-root " +
                                    shellQuoted(*data) + " --out " + shellQuoted(db) + " --quiet");
  ASSERT_EQ(made.exitCode, 0) << made.output;
  EXPECT_NE(made.output.find("plain/single/table_99cf659ae2fe4b87b72437fd995483b/01"),
            std::string::npos)
      << made.output;

  const fs::path grasps = dir.path() / "grasps.csv";
  const RunResult imported = runVisgrab("import acronym " + shellQuoted(h5) + " --db " +
                                        shellQuoted(db) + " --out " + shellQuoted(grasps));
  ASSERT_EQ(imported.exitCode, 0) << imported.output;
  EXPECT_NE(imported.output.find("2000 grasps imported, 0 rejected"), std::string::npos)
      << imported.output;

  const fs::path results = dir.path() / "results";
  const RunResult ran = runVisgrab("run --db " + shellQuoted(db) + " --grasps " +
                                   shellQuoted(grasps) + " --hand franka --protocol shake --out " +
                                   shellQuoted(results) + " --threads 2 --quiet");
  ASSERT_EQ(ran.exitCode, 0) << ran.output;
  EXPECT_NE(ran.output.find("2000 trials run"), std::string::npos) << ran.output;

  // Pictures replay a shake run's trial with the shake (the data folder's, by the recorded name
  // and hash): the run's own trial, same outcome and simulated time as trials.csv.
  const RunResult picture =
      runVisgrab("render --results " + shellQuoted(results) +
                 " --scene plain/single/table_99cf659ae2fe4b87b72437fd995483b/01 --grasp 0 --out " +
                 shellQuoted(dir.path() / "trial.png") + " --quiet");
  EXPECT_EQ(picture.exitCode, 0) << picture.output;
  EXPECT_EQ(picture.output.find("replayed as"), std::string::npos) << picture.output;
  EXPECT_TRUE(fs::exists(dir.path() / "trial.png"));

  const fs::path out = dir.path() / "agreement";
  const RunResult agreed = runVisgrab("agreement " + shellQuoted(results) + " --labels " +
                                      shellQuoted(h5) + " --out " + shellQuoted(out));
  ASSERT_EQ(agreed.exitCode, 0) << agreed.output;
  const auto all = agreementRow(out / "label-agreement.csv", "all");
  ASSERT_FALSE(all.empty()) << agreed.output;
  EXPECT_EQ(field(all, "trials"), 2000.0) << agreed.output;
  // FleX says 1,559 of the 2,000 grasps hold (78 %).
  EXPECT_EQ(field(all, "both_held") + field(all, "only_b_held"), 1559.0) << agreed.output;
  // The targets are 85 % agreement and kappa 0.6; measured on 29 Nov 2026: 81.3 % and
  // 0.440 (docs/validation.md, "Agreement with ACRONYM's labels", says why and what the
  // disagreements are). This guards the measured figures, with a margin for the time step's
  // chaos, until the protocol is better understood; it is not the target.
  EXPECT_GE(field(all, "observed_agreement"), 0.78) << agreed.output;
  EXPECT_GE(field(all, "kappa"), 0.38) << agreed.output;
  std::cout << agreed.output;
}

}  // namespace
