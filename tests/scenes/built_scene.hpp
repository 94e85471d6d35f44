#pragma once

#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <string>

#include "rw/geometry/mesh_loader.hpp"
#include "rw/math/rpy.hpp"
#include "rw/models/workcell.hpp"
#include "support/test_support.hpp"

/// A work cell built in code that uses every feature the workcell writer knows, for the writer
/// tests.
namespace visgrab::test::scenes {

/// Where the scene's frames are, for checks.
struct BuiltScene {
  /// The work cell.
  std::unique_ptr<rw::models::WorkCell> wc;
  /// The tetrahedron mesh file the scene uses.
  std::filesystem::path meshFile;
};

/// Writes a small tetrahedron as ASCII STL to `file`.
inline void writeTetrahedron(const std::filesystem::path& file) {
  writeFile(file,
            "solid tetra\n"
            " facet normal 0 0 -1\n  outer loop\n"
            "   vertex 0 0 0\n   vertex 0 0.02 0\n   vertex 0.02 0 0\n"
            "  endloop\n endfacet\n"
            " facet normal 0 -1 0\n  outer loop\n"
            "   vertex 0 0 0\n   vertex 0.02 0 0\n   vertex 0 0 0.02\n"
            "  endloop\n endfacet\n"
            " facet normal -1 0 0\n  outer loop\n"
            "   vertex 0 0 0\n   vertex 0 0 0.02\n   vertex 0 0.02 0\n"
            "  endloop\n endfacet\n"
            " facet normal 1 1 1\n  outer loop\n"
            "   vertex 0.02 0 0\n   vertex 0 0.02 0\n   vertex 0 0 0.02\n"
            "  endloop\n endfacet\n"
            "endsolid tetra\n");
}

/// Builds the scene; its mesh is written to `meshDir`/tetra.stl. Frames are created in an order
/// that RobWork's attachment rules cannot take as it is:
/// - "Mount", the first workcell-level frame by id, hangs on a device frame ("Arm.TCP"), so the
///   writer must put a child of WORLD ("Table") first;
/// - the tree device "Grip" is mounted on "Mount", the serial device "Arm" on WORLD.
/// It has a passive joint, a dependent prismatic joint with its own (raw) limits, Movable and
/// DAF frames, properties of each type, every primitive, a mesh used for collision only and
/// for drawing only, and a collision setup with volatile frames and proximity rules.
inline BuiltScene buildScene(const std::filesystem::path& meshDir) {
  using rw::kinematics::FrameId;
  using rw::kinematics::FrameSpec;
  using rw::kinematics::FrameTree;
  using rw::kinematics::FrameType;
  using rw::math::Q;
  using rw::math::Vector3D;
  namespace geo = rw::geometry;

  BuiltScene scene;
  scene.meshFile = meshDir / "tetra.stl";
  writeTetrahedron(scene.meshFile);
  scene.wc = std::make_unique<rw::models::WorkCell>("Built");
  rw::models::WorkCell& wc = *scene.wc;
  auto& tree = wc.frames();
  const auto add = [&](std::string name, FrameId parent, FrameType type, Vector3D rpy,
                       Vector3D pos) {
    FrameSpec spec;
    spec.name = std::move(name);
    spec.parent = parent;
    spec.type = type;
    spec.transform = rw::math::rpyTransform(rpy, pos);
    return spec;
  };

  // Serial device "Arm" on WORLD: J1 revolute, J2 prismatic, J3 passive revolute, TCP.
  FrameSpec base = add("Arm.Base", FrameTree::kWorld, FrameType::kFixed, {0, 0, 0}, {0, 0, 0.1});
  base.properties["maker"] = {std::string("VisGraB & co <test>"), "who built it"};
  const FrameId armBase = tree.add(base);
  FrameSpec j1 = add("Arm.J1", armBase, FrameType::kRevolute, {0.1, 0, 0}, {0, 0, 0.2});
  j1.limits = {-std::numbers::pi / 2, std::numbers::pi / 2, std::numbers::pi, 10.0};
  const FrameId armJ1 = tree.add(j1);
  FrameSpec j2 =
      add("Arm.J2", armJ1, FrameType::kPrismatic, {0, 1.5707963267948966, 0}, {0.3, 0, 0});
  j2.limits = {0.0, 0.3, 0.5, 2.0};
  const FrameId armJ2 = tree.add(j2);
  FrameSpec j3 = add("Arm.J3", armJ2, FrameType::kRevolute, {0, 0, 0.25}, {0, 0.05, 0});
  j3.passive = true;
  j3.limits.lower = -1.0;
  j3.limits.upper = 1.0;
  const FrameId armJ3 = tree.add(j3);
  const FrameId armTcp =
      tree.add(add("Arm.TCP", armJ3, FrameType::kFixed, {0, 0, 0}, {0, 0, 0.12345678901234}));

  // Workcell-level frames: "Mount" under the arm (first by id), "Table" on WORLD.
  const FrameId mount =
      tree.add(add("Mount", armTcp, FrameType::kFixed, {3.0, -0.2, 0.1}, {0.01, 0.02, 0.03}));
  FrameSpec table =
      add("Table", FrameTree::kWorld, FrameType::kFixed, {0.1, 0.2, 0.3}, {0.5, 0, 0.7});
  table.properties["height"] = {0.7, ""};
  table.properties["corners"] = {Q(Eigen::Vector4d(1, 2.5, -3, 1e-7)), "corner heights"};
  const FrameId tableId = tree.add(table);

  // Tree device "Grip" on Mount: R prismatic, L follows R (gain -1, offset 0.001), two tips.
  const FrameId gripBase =
      tree.add(add("Grip.Base", mount, FrameType::kMovable, {0, 0, 1.0}, {0, 0, 0.05}));
  FrameSpec r =
      add("Grip.R", gripBase, FrameType::kPrismatic, {0, 0, 1.5707963267948966}, {0, -0.01, 0.08});
  r.limits = {0.0, 0.04, 0.1, std::numeric_limits<double>::infinity()};
  const FrameId gripR = tree.add(r);
  FrameSpec rTip = add("Grip.R.Tip", gripR, FrameType::kFixed, {0, 0, 0}, {0, 0.03, 0});
  rTip.endEffector = true;
  const FrameId gripRTip = tree.add(rTip);
  FrameSpec l =
      add("Grip.L", gripBase, FrameType::kPrismatic, {0, 0, 1.5707963267948966}, {0, 0.01, 0.08});
  l.dependency = rw::kinematics::JointDependency{gripR, -1.0, 0.001};
  l.limits = {-0.04, 0.0, 0.1, std::numeric_limits<double>::infinity()};
  const FrameId gripL = tree.add(l);
  FrameSpec lTip = add("Grip.L.Tip", gripL, FrameType::kFixed, {0, 0, 0}, {0, 0.03, 0});
  lTip.endEffector = true;
  const FrameId gripLTip = tree.add(lTip);

  // A Movable DAF on the table.
  FrameSpec cup = add("Cup", tableId, FrameType::kMovable, {0.5, 0, 0}, {0.1, 0.1, 0.05});
  cup.daf = true;
  const FrameId cupId = tree.add(cup);

  rw::models::Device::Spec arm{"Arm", rw::models::Device::Kind::kSerial, armBase, {armTcp}, {}, {}};
  arm.configurations["Home"] = Q(Eigen::Vector2d(0.1, 0.2));
  arm.configurations["Ready"] = Q(Eigen::Vector2d(-0.5, 0.25));
  arm.properties["payload"] = {2.5, "kg"};
  arm.properties["gains"] = {Q(Eigen::Vector3d(1, 2, 3)), ""};
  wc.addDevice(arm);
  rw::models::Device::Spec grip{
      "Grip", rw::models::Device::Kind::kTree, gripBase, {gripRTip, gripLTip}, {}, {}};
  grip.configurations["Home"] = Q::Constant(1, 0.02);
  wc.addDevice(grip);

  // Geometry: every primitive, a mesh for collision only and one for drawing only.
  const auto instance = [](std::string name, std::shared_ptr<const geo::Geometry> g, Vector3D rpy,
                           Vector3D pos) {
    rw::models::GeometryInstance i;
    i.name = std::move(name);
    i.geometry = std::move(g);
    i.X_frame_geometry = rw::math::rpyTransform(rpy, pos);
    return i;
  };
  auto& floor = wc.objectOf(FrameTree::kWorld);
  floor.collision.push_back(instance("Floor", geo::Geometry::plane(), {0, 0, 0}, {0, 0, 0}));
  floor.visual.push_back(floor.collision.back());
  auto& top = wc.objectOf(tableId);
  top.collision.push_back(
      instance("Top", geo::Geometry::box(1, 0.8, 0.04), {0, 0, 0}, {0, 0, -0.02}));
  top.visual.push_back(top.collision.back());
  auto& cupObject = wc.objectOf(cupId);
  cupObject.collision.push_back(
      instance("Body", geo::Geometry::cylinder(0.04, 0.1), {0, 0.3, 0}, {0, 0, 0.05}));
  cupObject.visual.push_back(cupObject.collision.back());
  cupObject.collision.push_back(
      instance("Lid", geo::Geometry::sphere(0.02), {0, 0, 0}, {0, 0, 0.11}));
  cupObject.visual.push_back(
      instance("Handle", geo::Geometry::tube(0.01, 0.005, 0.03), {1.0, 0, 0}, {0.05, 0, 0.05}));
  cupObject.collision.push_back(
      instance("Foot", geo::Geometry::cone(0.03, 0.02), {0, 0, 3.14159}, {0, 0, -0.01}));
  const auto mesh = geo::Geometry::mesh(geo::loadMesh(scene.meshFile),
                                        std::filesystem::absolute(scene.meshFile).string());
  wc.objectOf(gripR).collision.push_back(instance("Pad", mesh, {0, 0, 0}, {0, 0.01, 0}));
  wc.objectOf(gripL).visual.push_back(instance("Logo", mesh, {0, 0, 0.5}, {0, 0.01, 0}));

  wc.properties()["author"] = {std::string("the writer tests"), ""};
  wc.properties()["scale"] = {1.0, "metres per unit"};

  auto& collision = wc.collisionSetup();
  collision.excludePairs = {{"Grip.Base", "Grip.R"}, {"Grip.Base", "Grip.L"}, {"Table", "Cup"}};
  collision.volatileFrames = {"Cup"};
  collision.excludeStaticPairs = true;
  auto& proximity = wc.proximitySetup();
  proximity.useExcludeStaticPairs = true;
  for (const auto& [a, b] : collision.excludePairs) proximity.rules.push_back({a, b, false});
  proximity.rules.push_back({"Arm.*", "Arm.*", false});
  proximity.rules.push_back({"Cup", "Grip.?", true});

  rw::kinematics::State state = tree.makeState();
  wc.findDevice("Arm")->setQ(arm.configurations["Home"], state);
  wc.findDevice("Grip")->setQ(grip.configurations["Home"], state);
  wc.setDefaultState(std::move(state));
  return scene;
}

}  // namespace visgrab::test::scenes
