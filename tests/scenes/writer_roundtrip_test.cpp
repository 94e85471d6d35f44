// load -> saveWorkCell -> load gives the same model: frames, joints, devices, geometry and
// setups, for RobWork's SDH2 and PG70 box scenes, the project's two hands and a scene built in
// code that uses every feature the writer knows.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "built_scene.hpp"
#include "rw/loaders/workcell_writer.hpp"
#include "scene_test_helpers.hpp"

namespace {

namespace fs = std::filesystem;
using rw::kinematics::Frame;
using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::PropertyMap;
using rw::kinematics::State;
using rw::math::Q;
using rw::models::Device;
using rw::models::GeometryInstance;
using rw::models::WorkCell;

constexpr double kPoseTolerance = 1e-9;

std::string nameOf(const WorkCell& wc, FrameId id) { return wc.frames().frame(id).name(); }

std::vector<std::string> namesOf(const WorkCell& wc, const std::vector<FrameId>& ids) {
  std::vector<std::string> names;
  for (const FrameId id : ids) names.push_back(nameOf(wc, id));
  return names;
}

// Limits are equal when both are the same infinity or agree to 1e-12 (relative).
void expectSameValue(double a, double b, const char* what) {
  if (std::isinf(a) || std::isinf(b)) {
    EXPECT_EQ(a, b) << what;
  } else {
    EXPECT_NEAR(a, b, 1e-12 * std::max(1.0, std::abs(a))) << what;
  }
}

void expectSameProperties(const PropertyMap& a, const PropertyMap& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, property] : a) {
    SCOPED_TRACE("property " + name);
    ASSERT_TRUE(b.contains(name));
    const auto& other = b.at(name);
    EXPECT_EQ(property.description, other.description);
    ASSERT_EQ(property.value.index(), other.value.index());
    if (const auto* q = std::get_if<Q>(&property.value)) {
      EXPECT_VECTOR_NEAR(*q, std::get<Q>(other.value), 0.0);
    } else {
      EXPECT_TRUE(property.value == other.value);
    }
  }
}

void expectSameFrame(const WorkCell& a, const Frame& fa, const State& sa, const WorkCell& b,
                     const Frame& fb, const State& sb) {
  if (fa.id() != FrameTree::kWorld) {
    EXPECT_EQ(nameOf(a, fa.parent()), nameOf(b, fb.parent()));
    EXPECT_EQ(nameOf(a, sa.parentOf(fa.id())), nameOf(b, sb.parentOf(fb.id())));
  }
  EXPECT_EQ(fa.type(), fb.type());
  EXPECT_EQ(fa.isEndEffector(), fb.isEndEffector());
  EXPECT_EQ(fa.isDaf(), fb.isDaf());
  EXPECT_EQ(fa.isPassive(), fb.isPassive());
  expectSameValue(fa.limits().lower, fb.limits().lower, "lower limit");
  expectSameValue(fa.limits().upper, fb.limits().upper, "upper limit");
  expectSameValue(fa.limits().velocity, fb.limits().velocity, "velocity limit");
  expectSameValue(fa.limits().acceleration, fb.limits().acceleration, "acceleration limit");
  ASSERT_EQ(fa.isDependent(), fb.isDependent());
  if (fa.isDependent()) {
    EXPECT_EQ(nameOf(a, fa.dependency()->owner), nameOf(b, fb.dependency()->owner));
    EXPECT_EQ(fa.dependency()->gain, fb.dependency()->gain);
    EXPECT_EQ(fa.dependency()->offset, fb.dependency()->offset);
  }
  expectSameProperties(fa.properties(), fb.properties());
  EXPECT_TRANSFORM_NEAR(fa.localTransform(sa), fb.localTransform(sb), kPoseTolerance);
}

void expectSameFrames(const WorkCell& a, const WorkCell& b) {
  std::set<std::string> namesA;
  std::set<std::string> namesB;
  for (const Frame& f : a.frames().frames()) namesA.insert(f.name());
  for (const Frame& f : b.frames().frames()) namesB.insert(f.name());
  ASSERT_EQ(namesA, namesB);
  const State sa = a.defaultState();
  const State sb = b.defaultState();
  for (const Frame& fa : a.frames().frames()) {
    SCOPED_TRACE("frame " + fa.name());
    expectSameFrame(a, fa, sa, b, b.frames().frame(b.findFrame(fa.name())), sb);
  }
}

// Junctions (legs by chain names and end frames) and the joint classes of a parallel device.
void expectSameParallel(const WorkCell& a, const rw::models::ParallelKinematics& pa,
                        const WorkCell& b, const rw::models::ParallelKinematics& pb) {
  EXPECT_EQ(pa.fullDof(), pb.fullDof());
  EXPECT_EQ(namesOf(a, pa.allJoints()), namesOf(b, pb.allJoints()));
  EXPECT_EQ(namesOf(a, pa.actuatedJoints()), namesOf(b, pb.actuatedJoints()));
  EXPECT_EQ(namesOf(a, pa.passiveJoints()), namesOf(b, pb.passiveJoints()));
  EXPECT_EQ(namesOf(a, pa.dependentJoints()), namesOf(b, pb.dependentJoints()));
  EXPECT_EQ(namesOf(a, pa.frames()), namesOf(b, pb.frames()));
  ASSERT_EQ(pa.junctions().size(), pb.junctions().size());
  for (std::size_t j = 0; j < pa.junctions().size(); ++j) {
    const auto& la = pa.junctions()[j].legs;
    const auto& lb = pb.junctions()[j].legs;
    ASSERT_EQ(la.size(), lb.size()) << "junction " << j;
    for (std::size_t i = 0; i < la.size(); ++i) {
      EXPECT_EQ(la[i].chains, lb[i].chains) << "junction " << j << " leg " << i;
      EXPECT_EQ(nameOf(a, la[i].start), nameOf(b, lb[i].start)) << "junction " << j;
      EXPECT_EQ(nameOf(a, la[i].end), nameOf(b, lb[i].end)) << "junction " << j;
    }
  }
}

void expectSameDevices(const WorkCell& a, const WorkCell& b) {
  ASSERT_EQ(a.devices().size(), b.devices().size());
  for (const auto& da : a.devices()) {
    SCOPED_TRACE("device " + da->name());
    const Device* db = b.findDevice(da->name());
    ASSERT_NE(db, nullptr);
    EXPECT_EQ(da->kind(), db->kind());
    EXPECT_EQ(da->dof(), db->dof());
    EXPECT_EQ(nameOf(a, da->base()), nameOf(b, db->base()));
    EXPECT_EQ(namesOf(a, da->ends()), namesOf(b, db->ends()));
    EXPECT_EQ(namesOf(a, da->joints()), namesOf(b, db->joints()));
    EXPECT_EQ(namesOf(a, da->activeJoints()), namesOf(b, db->activeJoints()));
    EXPECT_EQ(namesOf(a, da->frames()).size(), namesOf(b, db->frames()).size());
    ASSERT_EQ(da->parallel() == nullptr, db->parallel() == nullptr);
    if (da->parallel() != nullptr) expectSameParallel(a, *da->parallel(), b, *db->parallel());
    ASSERT_EQ(da->configurations().size(), db->configurations().size());
    for (const auto& [name, q] : da->configurations()) {
      ASSERT_TRUE(db->configurations().contains(name)) << name;
      EXPECT_VECTOR_NEAR(q, db->configurations().at(name), 0.0);
    }
    expectSameProperties(da->properties(), db->properties());
  }
}

// A random value in [lower, upper], or in [-1, 1] where a bound is infinite.
double randomIn(std::mt19937& rng, double lower, double upper) {
  if (!std::isfinite(lower) || !std::isfinite(upper)) {
    lower = -1.0;
    upper = 1.0;
  }
  return std::uniform_real_distribution<double>(lower, upper)(rng);
}

// Sets q on both devices; a parallel device's loops must close in both or in neither.
void setBoth(const Device& da, State& sa, const Device& db, State& sb, const Q& q) {
  bool closedA = true;
  bool closedB = true;
  try {
    da.setQ(q, sa);
  } catch (const rw::models::ClosureError&) {
    closedA = false;
  }
  try {
    db.setQ(q, sb);
  } catch (const rw::models::ClosureError&) {
    closedB = false;
  }
  EXPECT_EQ(closedA, closedB) << "device " << da.name();
}

// Every frame's world pose agrees at two random configurations (devices and Movable frames);
// a parallel device moves a little from its default configuration, where its loops close.
void expectSameWorldPoses(const WorkCell& a, const WorkCell& b) {
  std::mt19937 rng(20240521);
  for (int trial = 0; trial < 2; ++trial) {
    SCOPED_TRACE("random configuration " + std::to_string(trial));
    State sa = a.defaultState();
    State sb = b.defaultState();
    for (const auto& da : a.devices()) {
      Q q(da->dof());
      const Q lower = da->lowerLimits();
      const Q upper = da->upperLimits();
      for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = randomIn(rng, lower[i], upper[i]);
      if (da->parallel() != nullptr) q = da->getQ(sa) + 0.01 * (q - da->getQ(sa));
      setBoth(*da, sa, *b.findDevice(da->name()), sb, q);
    }
    for (const Frame& fa : a.frames().frames()) {
      if (fa.type() != rw::kinematics::FrameType::kMovable) continue;
      const auto X = rw::math::rpyTransform(
          rw::math::Vector3D(randomIn(rng, -3, 3), randomIn(rng, -1.5, 1.5), randomIn(rng, -3, 3)),
          rw::math::Vector3D(randomIn(rng, -1, 1), randomIn(rng, -1, 1), randomIn(rng, -1, 1)));
      fa.setMovableTransform(sa, X);
      b.frames().frame(b.findFrame(fa.name())).setMovableTransform(sb, X);
    }
    const rw::kinematics::FKTable fkA(a.frames(), sa);
    const rw::kinematics::FKTable fkB(b.frames(), sb);
    for (const Frame& fa : a.frames().frames()) {
      SCOPED_TRACE("frame " + fa.name());
      EXPECT_TRANSFORM_NEAR(fkA.worldTransform(fa.id()), fkB.worldTransform(b.findFrame(fa.name())),
                            kPoseTolerance);
    }
  }
}

bool sameShape(const GeometryInstance& a, const GeometryInstance& b) {
  const auto& ga = *a.geometry;
  const auto& gb = *b.geometry;
  if (a.name != b.name || ga.type() != gb.type() ||
      ga.parameters().size() != gb.parameters().size()) {
    return false;
  }
  for (std::size_t i = 0; i < ga.parameters().size(); ++i) {
    if (std::abs(ga.parameters()[i] - gb.parameters()[i]) > 1e-12) return false;
  }
  const double dp =
      (a.X_frame_geometry.matrix() - b.X_frame_geometry.matrix()).cwiseAbs().maxCoeff();
  return dp <= kPoseTolerance &&
         ga.triangles().triangles.size() == gb.triangles().triangles.size() &&
         ga.triangles().vertices.size() == gb.triangles().vertices.size() &&
         fs::path(ga.sourceFile()).filename() == fs::path(gb.sourceFile()).filename();
}

// The same instances, in any order (the writer groups Drawables before CollisionModels).
void expectSameInstances(const std::vector<GeometryInstance>& a,
                         const std::vector<GeometryInstance>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  std::vector<bool> used(b.size(), false);
  for (const GeometryInstance& ia : a) {
    bool found = false;
    for (std::size_t j = 0; j < b.size() && !found; ++j) {
      if (!used[j] && sameShape(ia, b[j])) used[j] = found = true;
    }
    EXPECT_TRUE(found) << what << " geometry \"" << ia.name << "\" ("
                       << rw::geometry::geometryTypeName(ia.geometry->type())
                       << ") has no equal after the round trip";
  }
}

void expectSameGeometry(const WorkCell& a, const WorkCell& b) {
  const auto nonEmpty = [](const WorkCell& wc) {
    return std::count_if(wc.objects().begin(), wc.objects().end(),
                         [](const auto& o) { return !o.collision.empty() || !o.visual.empty(); });
  };
  EXPECT_EQ(nonEmpty(a), nonEmpty(b));
  for (const auto& oa : a.objects()) {
    SCOPED_TRACE("geometry of " + nameOf(a, oa.frame));
    const auto* ob = b.findObject(b.findFrame(nameOf(a, oa.frame)));
    ASSERT_NE(ob, nullptr);
    expectSameInstances(oa.collision, ob->collision, "collision");
    expectSameInstances(oa.visual, ob->visual, "visual");
  }
}

std::set<std::pair<std::string, std::string>> unorderedPairs(
    const std::vector<std::pair<std::string, std::string>>& pairs) {
  std::set<std::pair<std::string, std::string>> set;
  for (const auto& [x, y] : pairs) set.insert(std::minmax(x, y));
  return set;
}

void expectSameSetups(const WorkCell& a, const WorkCell& b) {
  const auto& ca = a.collisionSetup();
  const auto& cb = b.collisionSetup();
  EXPECT_EQ(unorderedPairs(ca.excludePairs), unorderedPairs(cb.excludePairs));
  EXPECT_EQ(std::set<std::string>(ca.volatileFrames.begin(), ca.volatileFrames.end()),
            std::set<std::string>(cb.volatileFrames.begin(), cb.volatileFrames.end()));
  EXPECT_EQ(ca.excludeStaticPairs, cb.excludeStaticPairs);
  const auto& pa = a.proximitySetup();
  const auto& pb = b.proximitySetup();
  EXPECT_EQ(pa.useIncludeAll, pb.useIncludeAll);
  EXPECT_EQ(pa.useExcludeStaticPairs, pb.useExcludeStaticPairs);
  ASSERT_EQ(pa.rules.size(), pb.rules.size());
  for (std::size_t i = 0; i < pa.rules.size(); ++i) {
    EXPECT_EQ(pa.rules[i].patternA, pb.rules[i].patternA) << "rule " << i;
    EXPECT_EQ(pa.rules[i].patternB, pb.rules[i].patternB) << "rule " << i;
    EXPECT_EQ(pa.rules[i].include, pb.rules[i].include) << "rule " << i;
  }
}

void expectSameWorkCell(const WorkCell& a, const WorkCell& b) {
  EXPECT_EQ(a.name(), b.name());
  expectSameProperties(a.properties(), b.properties());
  // Later checks look frames and devices up by name: stop at a missing one.
  ASSERT_NO_FATAL_FAILURE(expectSameFrames(a, b));
  ASSERT_NO_FATAL_FAILURE(expectSameDevices(a, b));
  expectSameWorldPoses(a, b);
  expectSameGeometry(a, b);
  expectSameSetups(a, b);
}

// Saves `wc` to `dir`/copy.wc.xml, loads it back (without warnings) and compares.
void roundTrip(const WorkCell& wc, const fs::path& dir) {
  const fs::path file = dir / "copy.wc.xml";
  rw::loaders::saveWorkCell(wc, file);
  std::vector<rw::common::Diagnostic> warnings;
  const auto copy = rw::loaders::loadWorkCell(file, &warnings);
  for (const auto& w : warnings) ADD_FAILURE() << "warning on reload: " << w.format();
  expectSameWorkCell(wc, *copy);
}

struct SceneFile {
  const char* label;
  const char* path;  // relative to RW_COMPAT_DATA, or to the source folder
  bool compat;
};

void PrintTo(const SceneFile& scene, std::ostream* os) { *os << scene.path; }

class WriterRoundTrip : public ::testing::TestWithParam<SceneFile> {};

TEST_P(WriterRoundTrip, LoadsBackToTheSameModel) {
  const SceneFile& scene = GetParam();
  fs::path file;
  if (scene.compat) {
    REQUIRE_COMPAT_DATA(data);
    file = data / scene.path;
  } else {
    file = visgrab::test::sourceDir() / scene.path;
  }
  const auto original = visgrab::test::scenes::load(file);
  visgrab::test::TempDir dir;
  roundTrip(*original, dir.path());
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, WriterRoundTrip,
    ::testing::Values(SceneFile{"RobWorkSdh2", "devices/SDH2/SchunkHand.wc.xml", true},
                      SceneFile{"RobWorkPg70Box", "scene/grasping/pg70_box.wc.xml", true},
                      SceneFile{"RobWorkRobotiq", "devices/Robotiq-2-finger-85/robotiq.wc.xml",
                                true},
                      SceneFile{"ProjectSdh", "scenes/hands/sdh/sdh.wc.xml", false},
                      SceneFile{"ProjectPg70", "scenes/hands/pg70/pg70.wc.xml", false}),
    [](const ::testing::TestParamInfo<SceneFile>& param) { return param.param.label; });

TEST(WriterRoundTripBuilt, SceneBuiltInCodeLoadsBackToTheSameModel) {
  visgrab::test::TempDir dir;
  const auto scene = visgrab::test::scenes::buildScene(dir.path() / "meshes");
  fs::create_directories(dir.path() / "out");
  roundTrip(*scene.wc, dir.path() / "out");
}

// A parallel device written inline: nested SerialChains, a chain continuing another in a leg,
// a coupled (dependent) passive joint, device-level limits, a Home configuration.
TEST(WriterRoundTripBuilt, ParallelDeviceLoadsBackToTheSameModel) {
  const char* const xml = R"(<WorkCell name="Loops">
 <Frame name="Mount"><RPY>0 0 90</RPY><Pos>0 0 1</Pos></Frame>
 <ParallelDevice name="P">
  <Frame name="Base"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
  <SerialChain name="Crank">
   <Joint name="A" type="Revolute"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>
    <PosLimit min="-90" max="90"/></Joint>
   <Joint name="B" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>2 0 0</Pos></Joint>
   <Frame name="End"><RPY>0 0 0</RPY><Pos>2.5 0 0</Pos></Frame>
  </SerialChain>
  <Frame name="Ground" refframe="Base"><RPY>0 0 0</RPY><Pos>3 0 0</Pos></Frame>
  <SerialChain name="Rocker">
   <Joint name="C" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Joint>
   <SerialChain name="Tip">
    <Joint name="D" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>2 0 0</Pos></Joint>
   </SerialChain>
  </SerialChain>
  <Frame name="Extra" refframe="Crank.End"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
  <SerialChain name="Tool">
   <Joint name="E" type="Revolute" state="Passive"><RPY>0 0 0</RPY><Pos>0 0 0</Pos>
    <Depend on="Rocker.C" gain="0.5" offset="0.1"/></Joint>
  </SerialChain>
  <VelLimit refjoint="Crank.A" max="30"/>
  <Junction><Chains>Crank</Chains><Chains>Tip</Chains></Junction>
  <Q name="Home">0.5</Q>
 </ParallelDevice>
</WorkCell>
)";
  visgrab::test::TempDir dir;
  const auto original = rw::loaders::loadWorkCellFromString(xml, dir.path() / "loops.wc.xml");
  ASSERT_NE(original->findDevice("P")->parallel(), nullptr);
  roundTrip(*original, dir.path());
}

// The string form has no setup files; everything else loads back the same.
TEST(WriterRoundTripBuilt, StringFormLoadsBackFromAVirtualFile) {
  visgrab::test::TempDir dir;
  const auto scene = visgrab::test::scenes::buildScene(dir.path() / "meshes");
  fs::create_directories(dir.path() / "out");  // the mesh path goes through it ("../meshes")
  const std::string xml = rw::loaders::writeWorkCell(*scene.wc, dir.path() / "out");
  const auto copy = rw::loaders::loadWorkCellFromString(xml, dir.path() / "out" / "v.wc.xml");
  ASSERT_NO_FATAL_FAILURE(expectSameFrames(*scene.wc, *copy));
  ASSERT_NO_FATAL_FAILURE(expectSameDevices(*scene.wc, *copy));
  expectSameWorldPoses(*scene.wc, *copy);
  expectSameGeometry(*scene.wc, *copy);
}

}  // namespace
