#include "visgrab/taskio/grasp_file.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/test_support.hpp"
#include "visgrab/taskio/rwtask_io.hpp"

namespace visgrab::taskio {
namespace {

using rw::math::Q;
using rw::math::Vector3D;

const char* const kList = "# hand-written\ns,m,a,pose_q,0,0,0,1,0,0,0,1,0.5\ns,m,b,grip\n";

const char* const kExperiment =
    "<?xml version=\"1.0\"?>\n<!-- an experiment -->\n<visgrab><experiment id=\"e\">"
    "<sceneInfo><sceneID>s</sceneID></sceneInfo>\n"
    "<grasp id=\"a\"><pose><position>0 0 1000</position></pose><qopen>0</qopen>"
    "<qclose>1</qclose><maxtau/></grasp></experiment></visgrab>\n";

std::string rwTaskText(bool withScene, const std::string& refframe = "WORLD") {
  grasp::GraspRequest r;
  r.sceneId = "textured/single/cocacola/03";
  r.id = "g1";
  r.X_W_tcp = rw::math::makeTranslation(Vector3D(0.1, 0.2, 0.3));
  r.qOpen = Q::Constant(1, 0.035);
  r.qClosed = Q::Constant(1, 0.0);
  GraspTask task = fromGraspRequests({r}, "PG70", "PG70.TCPPG70");
  task.subTasks[0].refframe = refframe;
  if (!withScene) task.otherProperties.clear();
  return formatRwTask(task);
}

TEST(GraspFileTest, DetectsTheFormat) {
  EXPECT_EQ(detectGraspFileFormat(kList, "a"), GraspFileFormat::kGraspList);
  EXPECT_EQ(detectGraspFileFormat(kExperiment, "a"), GraspFileFormat::kExperiment);
  EXPECT_EQ(detectGraspFileFormat(rwTaskText(true), "a"), GraspFileFormat::kRwTask);
  EXPECT_EQ(detectGraspFileFormat("", "a"), GraspFileFormat::kGraspList);
  EXPECT_THROW(detectGraspFileFormat("<other/>", "a"), rw::common::LoadError);
}

TEST(GraspFileTest, ReadsAGraspList) {
  test::TempDir dir;
  const auto file = test::writeFile(dir.path() / "mine.csv", kList);
  const auto got = readGraspFile(file);
  ASSERT_EQ(got.requests.size(), 1u);
  EXPECT_EQ(got.requests[0].sourceFile, file.string());
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_EQ(got.rejected[0].line, 3);
}

TEST(GraspFileTest, ReadsAnExperiment) {
  test::TempDir dir;
  const auto got = readGraspFile(test::writeFile(dir.path() / "exp.xml", kExperiment));
  ASSERT_EQ(got.requests.size(), 1u);
  EXPECT_EQ(got.requests[0].method, "e");
  EXPECT_EQ(got.requests[0].sourceLine, 4);
  EXPECT_EQ(got.requests[0].X_W_tcp.translation(), Vector3D(0, 0, 1));
}

TEST(GraspFileTest, ReadsAnRwTaskWithSceneId) {
  test::TempDir dir;
  const auto got = readGraspFile(test::writeFile(dir.path() / "run.rwtask.xml", rwTaskText(true)));
  ASSERT_EQ(got.requests.size(), 1u);
  EXPECT_TRUE(got.rejected.empty());
  const auto& r = got.requests[0];
  EXPECT_EQ(r.sceneId, "textured/single/cocacola/03");
  EXPECT_EQ(r.method, "run");
  EXPECT_EQ(r.id, "g1");
  EXPECT_EQ(r.kind, grasp::GraspKind::kRaw);
  EXPECT_EQ(r.X_W_tcp.translation(), Vector3D(0.1, 0.2, 0.3));
  EXPECT_EQ(r.qOpen, Q::Constant(1, 0.035));
  EXPECT_GT(r.sourceLine, 0);
}

TEST(GraspFileTest, RwTaskWithoutSceneIdIsAnError) {
  test::TempDir dir;
  const auto file = test::writeFile(dir.path() / "run.rwtask.xml", rwTaskText(false));
  try {
    readGraspFile(file);
    FAIL() << "expected LoadError";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("SceneID"), std::string::npos) << e.what();
    EXPECT_EQ(e.diagnostics()[0].line, 2);
  }
}

TEST(GraspFileTest, RwTaskWithObjectRefframeRejectsItsTargets) {
  test::TempDir dir;
  const auto got =
      readGraspFile(test::writeFile(dir.path() / "t.rwtask.xml", rwTaskText(true, "object")));
  EXPECT_TRUE(got.requests.empty());
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_NE(got.rejected[0].message.find("refframe \"object\""), std::string::npos);
  EXPECT_GT(got.rejected[0].line, 0);
}

TEST(GraspFileTest, WholeFileProblemsThrow) {
  test::TempDir dir;
  EXPECT_THROW(readGraspFile(dir.path() / "missing.csv"), rw::common::LoadError);
  EXPECT_THROW(readGraspFile(test::writeFile(dir.path() / "bad.xml", "<visgrab><a></visgrab>")),
               rw::common::LoadError);
  EXPECT_THROW(readGraspFile(test::writeFile(dir.path() / "other.xml", "<root/>")),
               rw::common::LoadError);
}

TEST(GraspFileTest, FolderReadsAllFilesSortedByName) {
  test::TempDir dir;
  test::writeFile(dir.path() / "b_list.csv", kList);
  test::writeFile(dir.path() / "a_exp.xml", kExperiment);
  test::writeFile(dir.path() / "c.rwtask.xml", rwTaskText(true));
  test::writeFile(dir.path() / ".hidden", "garbage\n");
  std::filesystem::create_directory(dir.path() / "sub");
  const auto got = readGraspFolder(dir.path());
  ASSERT_EQ(got.requests.size(), 3u);
  EXPECT_EQ(got.requests[0].method, "e");
  EXPECT_EQ(got.requests[1].method, "m");
  EXPECT_EQ(got.requests[2].method, "c");
  ASSERT_EQ(got.rejected.size(), 1u);
  EXPECT_EQ(std::filesystem::path(got.rejected[0].file).filename(), "b_list.csv");
  EXPECT_THROW(readGraspFolder(dir.path() / "nope"), rw::common::LoadError);
}

}  // namespace
}  // namespace visgrab::taskio
