// The MJCF exporter of the MuJoCo comparison benchmark: the exported SDH box scene compiles in
// MuJoCo, its bodies sit where the project's forward kinematics puts them, its masses, inertias,
// friction pairs, motors and coupling are the dwc's, and what it cannot export is named.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mujoco/mjcf_export.hpp"
#include "mujoco/mujoco_grasp_trial.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using visgrab::mujoco::exportMjcf;

const rwsim::dynamics::DynamicWorkCell& sdhBox() {
  static const auto dwc = rwsim::loaders::loadDynamicWorkCell(
      visgrab::test::sourceDir() / "tests/rwsim/simulator/data/sdh_box.dwc.xml");
  return *dwc;
}

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// mj_loadXML on the exported text (through MuJoCo's virtual file system); fails the test with
// MuJoCo's message if it does not compile.
ModelPtr load(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  EXPECT_EQ(mj_makeEmptyFileVFS(vfs.get(), "m.xml", static_cast<int>(xml.size())), 0);
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "m.xml")], xml.data(), xml.size());
  char error[1000] = "";
  ModelPtr m(mj_loadXML("m.xml", vfs.get(), error, sizeof(error)));
  mj_deleteVFS(vfs.get());
  EXPECT_NE(m, nullptr) << error;
  return m;
}

int jointQpos(const mjModel* m, const std::string& name) {
  const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
  EXPECT_GE(j, 0) << name;
  return j < 0 ? 0 : m->jnt_qposadr[j];
}

// Sets the hand's joints in MuJoCo (dependent F3Joint1 from its coupling) and in a project state,
// then checks every body's world pose against the project's forward kinematics.
void expectBodiesAtFk(const Q& q) {
  const auto& dwc = sdhBox();
  const auto model = exportMjcf(dwc);
  const ModelPtr m = load(model.xml);
  ASSERT_NE(m, nullptr);
  const DataPtr d(mj_makeData(m.get()));
  rw::kinematics::State state = dwc.workcell().defaultState();
  const auto& hand = *dwc.device(dwc.findDevice("SchunkHand")).device;
  hand.setQ(q, state);
  const auto& tree = dwc.workcell().frames();
  for (const auto joint : hand.joints()) {
    const auto& f = tree.frame(joint);
    d->qpos[jointQpos(m.get(), f.name())] = f.jointValue(state);
  }
  mj_forward(m.get(), d.get());
  const rw::kinematics::FKTable fk(tree, state);
  for (std::size_t b = 0; b < dwc.bodies().size(); ++b) {
    const auto& body = dwc.bodies()[b];
    const int id = mj_name2id(m.get(), mjOBJ_BODY, model.bodyNames[b].c_str());
    ASSERT_GE(id, 0) << body.name;
    const Transform3D& X = fk.worldTransform(body.frame);
    const Vector3D p(d->xpos[3 * id], d->xpos[3 * id + 1], d->xpos[3 * id + 2]);
    EXPECT_LT((p - X.translation()).norm(), 1e-5) << body.name;
    const Eigen::Matrix3d R =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->xmat + 9 * id);
    EXPECT_LT((R - X.linear()).norm(), 1e-6) << body.name;
  }
}

TEST(MjcfExport, BodiesAtQZeroMatchTheProjectsForwardKinematics) { expectBodiesAtFk(Q::Zero(7)); }

TEST(MjcfExport, BodiesAtTheOpenPreshapeMatchTheProjectsForwardKinematics) {
  Q q(7);
  q << -1.048, 0.174, 0.5, -1.048, 0.174, -1.048, 0.174;  // the spread turned too
  expectBodiesAtFk(q);
}

TEST(MjcfExport, MassesCentresAndInertiasAreTheDwcs) {
  const auto& dwc = sdhBox();
  const auto model = exportMjcf(dwc);
  const ModelPtr m = load(model.xml);
  ASSERT_NE(m, nullptr);
  int rigid = 0;
  for (std::size_t b = 0; b < dwc.bodies().size(); ++b) {
    const auto& body = dwc.bodies()[b];
    if (body.kind != rwsim::dynamics::BodyKind::kRigid) continue;
    ++rigid;
    const int id = mj_name2id(m.get(), mjOBJ_BODY, body.name.c_str());
    ASSERT_GE(id, 0);
    EXPECT_NEAR(m->body_mass[id], body.mass.mass, 1e-12) << body.name;
    const Vector3D cog(m->body_ipos[3 * id], m->body_ipos[3 * id + 1], m->body_ipos[3 * id + 2]);
    EXPECT_LT((cog - body.mass.cog).norm(), 1e-12) << body.name;
    // MuJoCo keeps the principal moments and axes: R diag(I) R^T must give the full tensor back.
    const Eigen::Quaterniond iq(m->body_iquat[4 * id], m->body_iquat[4 * id + 1],
                                m->body_iquat[4 * id + 2], m->body_iquat[4 * id + 3]);
    const Eigen::Matrix3d R = iq.toRotationMatrix();
    const Eigen::Matrix3d I =
        R *
        Vector3D(m->body_inertia[3 * id], m->body_inertia[3 * id + 1], m->body_inertia[3 * id + 2])
            .asDiagonal() *
        R.transpose();
    // MuJoCo's eigen decomposition is iterative: 1e-7 of the tensor on the proximal links, whose
    // two largest moments differ by 0.3 %.
    EXPECT_LT((I - body.mass.inertia).norm(), 1e-6 * body.mass.inertia.norm()) << body.name;
  }
  EXPECT_EQ(rigid, 9);  // the box and eight links
}

double pairFriction(const mjModel* m, const std::string& g1, const std::string& g2) {
  const int a = mj_name2id(m, mjOBJ_GEOM, g1.c_str());
  const int b = mj_name2id(m, mjOBJ_GEOM, g2.c_str());
  for (int i = 0; i < m->npair; ++i) {
    if ((m->pair_geom1[i] == a && m->pair_geom2[i] == b) ||
        (m->pair_geom1[i] == b && m->pair_geom2[i] == a)) {
      return m->pair_friction[5 * i];
    }
  }
  return -1.0;  // no pair
}

TEST(MjcfExport, ContactPairsCarryTheMaterialMapsFriction) {
  const auto model = exportMjcf(sdhBox());
  const ModelPtr m = load(model.xml);
  ASSERT_NE(m, nullptr);
  const std::string tip1 = "SchunkHand.f1.Joint3/FingertipPad";
  const std::string tip2 = "SchunkHand.f2.Joint3/FingertipPad";
  ASSERT_GE(mj_name2id(m.get(), mjOBJ_GEOM, tip1.c_str()), 0) << model.xml;
  EXPECT_DOUBLE_EQ(pairFriction(m.get(), tip1, "Box/BoxGeo"), 0.6);              // Finger-Object
  EXPECT_DOUBLE_EQ(pairFriction(m.get(), tip1, tip2), 0.8);                      // Finger-Finger
  EXPECT_DOUBLE_EQ(pairFriction(m.get(), "Box/BoxGeo", "Table/TableGeo"), 0.4);  // Object-Table
  // Never between two non-moving bodies, nor across a joint, nor pairs sdh.prox.xml excludes.
  EXPECT_LT(pairFriction(m.get(), "SchunkHand.Base/Palm", "Table/TableGeo"), 0.0);
  EXPECT_LT(pairFriction(m.get(), "SchunkHand.f1.Joint2/ProximalLink", tip1), 0.0);
  EXPECT_LT(pairFriction(m.get(), "SchunkHand.Base/Palm", "SchunkHand.F2Joint1/F2BaseBlock"), 0.0);
  // Only the explicit pairs collide.
  for (int g = 0; g < m->ngeom; ++g) {
    EXPECT_EQ(m->geom_contype[g], 0);
    EXPECT_EQ(m->geom_conaffinity[g], 0);
  }
}

TEST(MjcfExport, MotorsCouplingAndBaseSlidesAreExported) {
  const auto& dwc = sdhBox();
  const auto model = exportMjcf(dwc);
  const ModelPtr m = load(model.xml);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->nu, 7 + 3);  // one servo per active joint, three for the base's slides
  const auto& rd = dwc.device(dwc.findDevice("SchunkHand"));
  const auto& tree = dwc.workcell().frames();
  for (std::size_t k = 0; k < rd.device->joints().size(); ++k) {
    const auto& f = tree.frame(rd.device->joints()[k]);
    const int a = mj_name2id(m.get(), mjOBJ_ACTUATOR, f.name().c_str());
    if (f.isDependent()) {
      EXPECT_LT(a, 0) << f.name();
      continue;
    }
    ASSERT_GE(a, 0) << f.name();
    EXPECT_EQ(m->actuator_forcerange[2 * a + 1], rd.forceLimits[k]) << f.name();
    EXPECT_EQ(m->actuator_forcerange[2 * a], -rd.forceLimits[k]) << f.name();
    const int j = mj_name2id(m.get(), mjOBJ_JOINT, f.name().c_str());
    EXPECT_NEAR(m->jnt_range[2 * j], f.limits().lower, 1e-12);
    EXPECT_NEAR(m->jnt_range[2 * j + 1], f.limits().upper, 1e-12);
  }
  ASSERT_EQ(m->neq, 1);  // F3Joint1 = -F2Joint1
  EXPECT_EQ(m->eq_type[0], mjEQ_JOINT);
  EXPECT_EQ(m->eq_obj1id[0], mj_name2id(m.get(), mjOBJ_JOINT, "SchunkHand.F3Joint1"));
  EXPECT_EQ(m->eq_obj2id[0], mj_name2id(m.get(), mjOBJ_JOINT, "SchunkHand.F2Joint1"));
  EXPECT_EQ(m->eq_data[0], 0.0);
  EXPECT_EQ(m->eq_data[1], -1.0);
  ASSERT_EQ(model.slideJoints[dwc.findBody("SchunkHand.Base").index()].size(), 3u);
}

TEST(MjcfExport, UnsupportedGeometryIsNamedWithItsFrame) {
  const std::string wc = R"(<WorkCell name="ConeScene">
  <Frame name="Funnel" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.1</Pos>
    <Drawable name="FunnelGeo"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Cone radius="0.03" z="0.08"/></Drawable>
  </Frame>
</WorkCell>)";
  const std::string dwcXml = R"(<DynamicWorkcell workcell="cone.wc.xml">
  <Include file="materials.xml"/>
  <RigidBody frame="Funnel"><Mass>0.1</Mass><EstimateInertia/></RigidBody>
</DynamicWorkcell>)";
  const auto dwc = rwsim::loaders::loadDynamicWorkCellFromStrings(
      dwcXml, wc, visgrab::test::sourceDir() / "scenes/cone.dwc.xml");
  try {
    exportMjcf(*dwc);
    FAIL() << "a cone was exported";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame 'Funnel'"), std::string::npos) << what;
    EXPECT_NE(what.find("Cone 'FunnelGeo'"), std::string::npos) << what;
  }
}

TEST(MjcfExport, APlaneOnAMovingBodyIsRefused) {
  const std::string wc = R"(<WorkCell name="PlaneScene">
  <Frame name="Raft" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.1</Pos>
    <Drawable name="RaftBox"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.1" y="0.1" z="0.02"/></Drawable>
    <Drawable name="RaftTop"><RPY>0 0 0</RPY><Pos>0 0 0.01</Pos><Plane/></Drawable>
  </Frame>
</WorkCell>)";
  const std::string dwcXml = R"(<DynamicWorkcell workcell="plane.wc.xml">
  <Include file="materials.xml"/>
  <RigidBody frame="Raft"><Mass>0.1</Mass><COG>0 0 0</COG><Inertia>1e-4 0 0 0 1e-4 0 0 0 1e-4</Inertia></RigidBody>
</DynamicWorkcell>)";
  const auto dwc = rwsim::loaders::loadDynamicWorkCellFromStrings(
      dwcXml, wc, visgrab::test::sourceDir() / "scenes/plane.dwc.xml");
  try {
    exportMjcf(*dwc);
    FAIL() << "a plane on a rigid body was exported";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame 'Raft'"), std::string::npos) << what;
    EXPECT_NE(what.find("Plane 'RaftTop'"), std::string::npos) << what;
    EXPECT_NE(what.find("static"), std::string::npos) << what;
  }
}

TEST(MjcfExport, TheMujocoTrialHoldsTheBox) {
  const auto& dwc = sdhBox();
  const auto model = exportMjcf(dwc);
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = "SchunkHand";
  setup.tcpFrame = "SchunkHand.SDHTCP";
  setup.computeGws = false;
  visgrab::mujoco::MujocoGraspTrial trial(dwc, model, setup);
  rwsim::simulator::GraspParameters g;
  g.X_W_tcp = rw::math::rpyTransform(Vector3D(0, std::numbers::pi, 0), Vector3D(0, 0, 0.05));
  g.qOpen = Q(7);
  g.qOpen << -1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174;
  g.qClosed = Q(7);
  g.qClosed << 0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349;
  g.tauMax = Q(7);
  g.tauMax << 2.1, 1.4, 2.1, 1.05, 0.7, 1.05, 0.7;
  const auto result = trial.run(g, dwc.workcell().defaultState());
  EXPECT_EQ(result.outcome, rwsim::simulator::GraspOutcome::kStable) << result.detail;
  EXPECT_LT(result.drift, 0.01);
  // Closing takes at least minCloseTime, the lift 0.1 m at 0.5 m/s and 1 m/s^2 0.45 s, then
  // 0.2 s of settling.
  EXPECT_GT(result.simulatedTime, 0.2 + 0.45 + 0.2 - 1e-6);
  // The same trial placed with the hand turned about z: the base's slides cannot turn it.
  g.X_W_tcp = rw::math::rpyTransform(Vector3D(0.3, std::numbers::pi, 0), Vector3D(0, 0, 0.05));
  EXPECT_THROW(trial.run(g, dwc.workcell().defaultState()), std::invalid_argument);
}

}  // namespace
