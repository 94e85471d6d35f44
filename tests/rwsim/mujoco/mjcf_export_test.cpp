// The MJCF export of the MuJoCo engine: the exported SDH box scene compiles in MuJoCo, its bodies
// sit where the project's forward kinematics puts them, its masses, inertias, friction pairs,
// servos and coupling are the dwc's; convex meshes, cones and frusta become geoms whose vertices
// lie where the dwc's do; and what MuJoCo cannot represent is refused, naming the frame.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "rw/geometry/geometry.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/mujoco/mjcf_export.hpp"
#include "rwsim/simulator/sim_test_scenes.hpp"
#include "support/test_support.hpp"

namespace {

using rw::math::Q;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::mujoco::exportMjcf;
using visgrab::test::sim::SceneBuilder;

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
  EXPECT_DOUBLE_EQ(pairFriction(m.get(), tip1, "Box/BoxGeo"), 0.6);  // Finger-Object
  EXPECT_DOUBLE_EQ(pairFriction(m.get(), tip1, tip2), 0.8);          // Finger-Finger
  // Object-Table: a box meets the table box's top face through its plane (MuJoCo 2.2.2's
  // box-box collider gives phantom deep contacts for boxes resting face to face).
  EXPECT_DOUBLE_EQ(pairFriction(m.get(), "Box/BoxGeo", "Table/TableGeo#top"), 0.4);
  EXPECT_LT(pairFriction(m.get(), "Box/BoxGeo", "Table/TableGeo"), 0.0);
  const int plane = mj_name2id(m.get(), mjOBJ_GEOM, "Table/TableGeo#top");
  ASSERT_GE(plane, 0);
  EXPECT_EQ(m->geom_type[plane], mjGEOM_PLANE);
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

TEST(MjcfExport, ServosCouplingAndBaseJointsAreExported) {
  const auto& dwc = sdhBox();
  rwsim::mujoco::MujocoOptions options;
  options.motorGain = 3.5;
  const auto model = exportMjcf(dwc, options);
  const ModelPtr m = load(model.xml);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->nu, 7);  // one velocity servo per active joint; the base is driven directly
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
    // A velocity servo: force = kv ctrl - kv qdot.
    EXPECT_EQ(m->actuator_gainprm[mjNGAIN * a], 3.5) << f.name();
    EXPECT_EQ(m->actuator_biasprm[mjNBIAS * a + 2], -3.5) << f.name();
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
  // The kinematic base: three slides, three hinges, heavy armature.
  const auto& base = model.kinematicJoints[dwc.findBody("SchunkHand.Base").index()];
  ASSERT_EQ(base.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    const int j = mj_name2id(m.get(), mjOBJ_JOINT, base[k].c_str());
    ASSERT_GE(j, 0) << base[k];
    EXPECT_EQ(m->jnt_type[j], k < 3 ? mjJNT_SLIDE : mjJNT_HINGE) << base[k];
    EXPECT_EQ(m->dof_armature[m->jnt_dofadr[j]], options.kinematicArmature) << base[k];
  }
}

TEST(MjcfExport, ATubeIsRefusedNamingItsFrame) {
  const std::string wc = R"(<WorkCell name="TubeScene">
  <Frame name="Pipe" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.1</Pos>
    <Drawable name="PipeGeo"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Tube radius="0.03" thickness="0.005" z="0.08"/></Drawable>
  </Frame>
</WorkCell>)";
  const std::string dwcXml = R"(<DynamicWorkcell workcell="tube.wc.xml">
  <Include file="materials.xml"/>
  <RigidBody frame="Pipe"><Mass>0.1</Mass><COG>0 0 0</COG><Inertia>1e-4 0 0 0 1e-4 0 0 0 1e-4</Inertia></RigidBody>
</DynamicWorkcell>)";
  const auto dwc = rwsim::loaders::loadDynamicWorkCellFromStrings(
      dwcXml, wc, visgrab::test::sourceDir() / "scenes/tube.dwc.xml");
  try {
    exportMjcf(*dwc);
    FAIL() << "a tube was exported";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame 'Pipe'"), std::string::npos) << what;
    EXPECT_NE(what.find("Tube 'PipeGeo'"), std::string::npos) << what;
    EXPECT_NE(what.find("not convex"), std::string::npos) << what;
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

// A triangle mesh geometry from vertices and outward triangles.
std::shared_ptr<const rw::geometry::Geometry> meshOf(
    std::vector<Vector3D> vertices, std::vector<std::array<std::uint32_t, 3>> tri) {
  auto mesh = std::make_shared<rw::geometry::TriMesh>();
  mesh->vertices = std::move(vertices);
  mesh->triangles = std::move(tri);
  return rw::geometry::Geometry::mesh(mesh, "test.stl");
}

// A unit cube's corners scaled by `size` and centred at 0, with its 12 outward triangles.
std::shared_ptr<const rw::geometry::Geometry> cuboid(const Vector3D& size, const Transform3D& X) {
  std::vector<Vector3D> v;
  for (int i = 0; i < 8; ++i) {
    v.push_back(X * Vector3D(((i & 1) ? 0.5 : -0.5) * size.x(), ((i & 2) ? 0.5 : -0.5) * size.y(),
                             ((i & 4) ? 0.5 : -0.5) * size.z()));
  }
  return meshOf(v, {{0, 2, 1},
                    {1, 2, 3},
                    {4, 5, 6},
                    {5, 7, 6},
                    {0, 1, 4},
                    {1, 5, 4},
                    {2, 6, 3},
                    {3, 6, 7},
                    {0, 4, 2},
                    {2, 4, 6},
                    {1, 3, 5},
                    {3, 7, 5}});
}

// One rigid body "Piece" carrying `geometry` at X_W, exported and compiled.
struct PieceModel {
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc;
  ModelPtr m;
  DataPtr d;
};

PieceModel exportPiece(std::shared_ptr<const rw::geometry::Geometry> geometry,
                       const Transform3D& X_W) {
  SceneBuilder scene("piece");
  scene.addBody("Piece", X_W, std::move(geometry), 0.1, Eigen::Matrix3d::Identity() * 1e-4);
  PieceModel out;
  out.dwc = scene.build();
  out.m = load(exportMjcf(*out.dwc).xml);
  if (out.m) {
    out.d.reset(mj_makeData(out.m.get()));
    mj_forward(out.m.get(), out.d.get());
  }
  return out;
}

// The world positions of a mesh geom's vertices (MuJoCo stores them about the mesh's centroid).
std::vector<Vector3D> meshVerticesInWorld(const mjModel* m, const mjData* d, int geom) {
  const int mesh = m->geom_dataid[geom];
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(d->geom_xmat + 9 * geom);
  const Vector3D p(d->geom_xpos[3 * geom], d->geom_xpos[3 * geom + 1], d->geom_xpos[3 * geom + 2]);
  std::vector<Vector3D> out;
  for (int i = 0; i < m->mesh_vertnum[mesh]; ++i) {
    const float* v = m->mesh_vert + 3 * (m->mesh_vertadr[mesh] + i);
    out.push_back(p + R * Vector3D(v[0], v[1], v[2]));
  }
  return out;
}

double distanceToNearest(const Vector3D& p, const std::vector<Vector3D>& points) {
  double best = 1e9;
  for (const Vector3D& q : points) best = std::min(best, (p - q).norm());
  return best;
}

const Transform3D kTilted =
    rw::math::rpyTransform(Vector3D(0.3, -0.4, 1.1), Vector3D(0.1, 0.2, 0.3));

TEST(MjcfExport, AConvexMeshIsAMeshGeomWithItsVerticesInPlace) {
  const std::vector<Vector3D> corners = {Vector3D(0, 0, 0), Vector3D(0.05, 0, 0),
                                         Vector3D(0, 0.04, 0), Vector3D(0.01, 0.01, 0.03)};
  const auto tetra = meshOf(corners, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  ASSERT_TRUE(tetra->isConvex());
  const PieceModel p = exportPiece(tetra, kTilted);
  ASSERT_NE(p.m, nullptr);
  ASSERT_EQ(p.m->ngeom, 1);
  EXPECT_EQ(p.m->geom_type[0], mjGEOM_MESH);
  const auto world = meshVerticesInWorld(p.m.get(), p.d.get(), 0);
  ASSERT_EQ(world.size(), 4u);
  for (const Vector3D& c : corners) {
    EXPECT_LT(distanceToNearest(kTilted * c, world), 1e-6);  // MuJoCo keeps floats
  }
}

TEST(MjcfExport, ACuboidMeshIsABox) {
  const Transform3D X_frame_mesh =
      rw::math::rpyTransform(Vector3D(0.2, 0.0, 0.5), Vector3D(0.01, -0.02, 0.03));
  const PieceModel p = exportPiece(cuboid(Vector3D(0.06, 0.1, 0.2), X_frame_mesh), kTilted);
  ASSERT_NE(p.m, nullptr);
  ASSERT_EQ(p.m->ngeom, 1);
  ASSERT_EQ(p.m->geom_type[0], mjGEOM_BOX);
  std::vector<double> half(p.m->geom_size, p.m->geom_size + 3);
  std::sort(half.begin(), half.end());
  EXPECT_NEAR(half[0], 0.03, 1e-12);
  EXPECT_NEAR(half[1], 0.05, 1e-12);
  EXPECT_NEAR(half[2], 0.1, 1e-12);
  const Vector3D centre(p.d->geom_xpos[0], p.d->geom_xpos[1], p.d->geom_xpos[2]);
  EXPECT_LT((centre - (kTilted * X_frame_mesh).translation()).norm(), 1e-9);
}

TEST(MjcfExport, ConesAndFrustaAreHullsOfManySidedPolygons) {
  const PieceModel cone = exportPiece(rw::geometry::Geometry::cone(0.03, 0.08), kTilted);
  ASSERT_NE(cone.m, nullptr);
  ASSERT_EQ(cone.m->geom_type[0], mjGEOM_MESH);
  // The apex (z = -h/2) and 64 points on the base circle (z = +h/2, r = 0.03).
  const auto v = meshVerticesInWorld(cone.m.get(), cone.d.get(), 0);
  ASSERT_EQ(v.size(), 65u);
  EXPECT_LT(distanceToNearest(kTilted * Vector3D(0, 0, -0.04), v), 1e-6);
  const Transform3D X_W_cone = kTilted.inverse();
  for (const Vector3D& w : v) {
    const Vector3D local = X_W_cone * w;
    if (local.z() < 0.0) continue;
    EXPECT_NEAR(local.z(), 0.04, 1e-6);
    EXPECT_NEAR(local.head<2>().norm(), 0.03, 1e-6);
  }
  const PieceModel frustum =
      exportPiece(rw::geometry::Geometry::frustum(0.03, 0.02, 0.05), Transform3D::Identity());
  ASSERT_NE(frustum.m, nullptr);
  ASSERT_EQ(frustum.m->geom_type[0], mjGEOM_MESH);
  const auto f = meshVerticesInWorld(frustum.m.get(), frustum.d.get(), 0);
  ASSERT_EQ(f.size(), 128u);
  for (const Vector3D& w : f) {
    EXPECT_NEAR(std::abs(w.z()), 0.025, 1e-6);
    EXPECT_NEAR(w.head<2>().norm(), w.z() < 0.0 ? 0.03 : 0.02, 1e-6);
  }
}

TEST(MjcfExport, ANonConvexMeshIsRefusedNamingItsFrame) {
  // A cube with one corner pushed in towards its centre: a dent.
  auto g = cuboid(Vector3D(0.1, 0.1, 0.1), Transform3D::Identity());
  auto mesh = std::make_shared<rw::geometry::TriMesh>(g->triangles());
  for (auto& v : mesh->vertices) {
    if (v.x() > 0 && v.y() > 0 && v.z() > 0) v = Vector3D(0.01, 0.01, 0.01);
  }
  const auto dented = rw::geometry::Geometry::mesh(mesh, "dented.stl");
  ASSERT_FALSE(dented->isConvex());
  SceneBuilder scene("dented");
  scene.addBody("Dented", Transform3D::Identity(), dented, 0.1, Eigen::Matrix3d::Identity() * 1e-4);
  const auto dwc = scene.build();
  try {
    exportMjcf(*dwc);
    FAIL() << "a non-convex mesh was exported";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame 'Dented'"), std::string::npos) << what;
    EXPECT_NE(what.find("dented.stl"), std::string::npos) << what;
    EXPECT_NE(what.find("not convex"), std::string::npos) << what;
  }
}

}  // namespace
