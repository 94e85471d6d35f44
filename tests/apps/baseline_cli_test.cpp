// `visgrab baseline` on two scenes of the shared test database (one plain, one textured): the
// grasp list it writes, its independence of the thread count, the --debug pictures and the
// command-line mistakes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>

#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "support/visgrab_cli.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::test::RunResult;
using visgrab::test::runVisgrab;
using visgrab::test::shellQuoted;

// Two scenes of the shared database: a box on the plain table, a can on the textured one.
constexpr const char* kPlainScene = "plain/single/saltbox/01";
constexpr const char* kTexturedScene = "textured/single/cocacola/01";
const std::string kTwoScenes = std::string("'") + kPlainScene + ";" + kTexturedScene + "'";

std::string baselineArgs(const fs::path& out, const std::string& more) {
  return "baseline --db " + shellQuoted(visgrab::test::testDatabasePath()) + " --scenes " +
         kTwoScenes + " --out " + shellQuoted(out) + " " + more;
}

std::string readAll(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(BaselineCli, WritesAtMostPerTypeContactGraspsPerSceneAndMethod) {
  visgrab::test::TempDir dir;
  const fs::path file = dir.path() / "grasps" / "baseline.csv";
  const RunResult r = runVisgrab(baselineArgs(file, "--per-type 5 --threads 2"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("grasps in " + file.string()), std::string::npos) << r.output;

  const auto contents = visgrab::taskio::readGraspFile(file);
  EXPECT_TRUE(contents.rejected.empty()) << contents.rejected.front().format();
  EXPECT_TRUE(contents.warnings.empty()) << contents.warnings.front().format();
  ASSERT_FALSE(contents.requests.empty()) << r.output;
  const std::set<std::string> methods = {"s2EGA1", "s2EGA3", "s3EGA1"};
  const std::regex id("(s2EGA1|s2EGA3|s3EGA1)-[0-9][0-9]");
  std::map<std::pair<std::string, std::string>, int> perSceneAndMethod;
  for (const auto& g : contents.requests) {
    EXPECT_TRUE(g.sceneId == kPlainScene || g.sceneId == kTexturedScene) << g.sceneId;
    EXPECT_EQ(g.kind, visgrab::grasp::GraspKind::kContacts) << g.sceneId << " " << g.id;
    EXPECT_TRUE(methods.count(g.method)) << g.method;
    EXPECT_TRUE(std::regex_match(g.id, id)) << g.id;
    EXPECT_EQ(g.id.substr(0, g.method.size()), g.method) << g.id;
    ++perSceneAndMethod[{g.sceneId, g.method}];
  }
  for (const auto& [key, n] : perSceneAndMethod) EXPECT_LE(n, 5) << key.first << " " << key.second;
  // Both scenes have grasps.
  std::set<std::string> scenes;
  for (const auto& [key, n] : perSceneAndMethod) scenes.insert(key.first);
  EXPECT_EQ(scenes.size(), 2u) << r.output;

  // One thread: the same file, byte for byte.
  const fs::path again = dir.path() / "again.csv";
  const RunResult one = runVisgrab(baselineArgs(again, "--per-type 5 --threads 1 --quiet"));
  ASSERT_EQ(one.exitCode, 0) << one.output;
  EXPECT_EQ(readAll(again), readAll(file));
}

// --preshape: the same scenes' two-contact grasps, each as a pre-shape grasp with its TCP midway
// between its contacts (checked against the contact grasps of a run without --preshape).
TEST(BaselineCli, PreshapeWritesTheTwoContactGraspsAsPreshapeGrasps) {
  visgrab::test::TempDir dir;
  const RunResult contacts = runVisgrab(baselineArgs(dir.path() / "c.csv", "--per-type 4"));
  ASSERT_EQ(contacts.exitCode, 0) << contacts.output;
  const RunResult preshapes =
      runVisgrab(baselineArgs(dir.path() / "p.csv", "--per-type 4 --preshape wide"));
  ASSERT_EQ(preshapes.exitCode, 0) << preshapes.output;
  const auto c = visgrab::taskio::readGraspFile(dir.path() / "c.csv");
  const auto p = visgrab::taskio::readGraspFile(dir.path() / "p.csv");
  std::map<std::string, const visgrab::grasp::GraspRequest*> byKey;
  for (const auto& g : c.requests) byKey[g.sceneId + " " + g.id] = &g;
  int twoContact = 0;
  for (const auto& g : c.requests) twoContact += g.contacts.size() == 2 ? 1 : 0;
  ASSERT_GT(twoContact, 0);
  EXPECT_EQ(static_cast<int>(p.requests.size()), twoContact);
  for (const auto& g : p.requests) {
    EXPECT_EQ(g.kind, visgrab::grasp::GraspKind::kPreshape);
    EXPECT_EQ(g.preshape, "wide");
    const auto* original = byKey.at(g.sceneId + " " + g.id);
    ASSERT_EQ(original->contacts.size(), 2u);
    const rw::math::Vector3D mid =
        0.5 * (original->contacts[0].position + original->contacts[1].position);
    EXPECT_LT((g.X_W_tcp.translation() - mid).norm(), 1e-6) << g.id;  // grasp lists: 7+ digits
  }
}

TEST(BaselineCli, DebugWritesOnePicturePerScene) {
  visgrab::test::TempDir dir;
  const fs::path pictures = dir.path() / "debug";
  const RunResult r = runVisgrab(baselineArgs(
      dir.path() / "g.csv", "--per-type 2 --threads 2 --quiet --debug " + shellQuoted(pictures)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(pictures)) {
    names.insert(entry.path().filename().string());
    EXPECT_EQ(readAll(entry.path()).substr(0, 8), "\x89PNG\r\n\x1a\n") << entry.path();
  }
  EXPECT_EQ(names, (std::set<std::string>{"plain_single_saltbox_01.png",
                                          "textured_single_cocacola_01.png"}));
}

TEST(BaselineCli, CommandLineMistakesExitWithTwoAndNameTheProblem) {
  visgrab::test::TempDir dir;
  const std::string db = shellQuoted(visgrab::test::testDatabasePath());
  const std::string out = shellQuoted(dir.path() / "g.csv");
  const std::pair<std::string, std::string> cases[] = {
      {"baseline --out " + out, "baseline: --db DIR|MANIFEST is required"},
      {"baseline --db " + db, "baseline: --out GRASPS"},
      {"baseline --db " + db + " --out " + out + " --per-type 0",
       "baseline: --per-type needs an integer >= 1"},
      {"baseline --db " + db + " --out " + out + " --no-such-option 1",
       "unknown option --no-such-option"},
      // A valid filter that none of the shared database's scenes match.
      {"baseline --db " + db + " --out " + out + " --scenes 'textured/single/breadbox/*'",
       "selects no scene"},
  };
  for (const auto& [args, message] : cases) {
    const RunResult r = runVisgrab(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "g.csv"));
}

TEST(BaselineCli, AMissingDatabaseIsBadInputNamingThePath) {
  visgrab::test::TempDir dir;
  const fs::path missing = dir.path() / "no-database-here";
  const RunResult r = runVisgrab("baseline --db " + shellQuoted(missing) + " --out " +
                                 shellQuoted(dir.path() / "g.csv"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(missing.string()), std::string::npos) << r.output;
}

}  // namespace
