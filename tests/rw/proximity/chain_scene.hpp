#pragma once

#include <array>
#include <memory>
#include <string>

#include "proximity_test_util.hpp"
#include "rw/models/workcell.hpp"

/// Workcells built in code for the frame-level proximity tests.
namespace rw::proximity::test {

using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameType;
using rw::models::WorkCell;

/// Adds a frame and returns its id.
inline FrameId addFrame(WorkCell& wc, const std::string& name, FrameId parent, FrameType type,
                        const Transform3D& X = Transform3D::Identity(), bool daf = false) {
  FrameSpec spec;
  spec.name = name;
  spec.parent = parent;
  spec.type = type;
  spec.transform = X;
  spec.daf = daf;
  return wc.frames().add(std::move(spec));
}

/// Puts `geometry` on `frame` at X_frame_geometry.
inline void addGeometry(WorkCell& wc, FrameId frame,
                        std::shared_ptr<const rw::geometry::Geometry> geometry,
                        const Transform3D& X_frame_geometry = Transform3D::Identity()) {
  rw::models::GeometryInstance instance;
  instance.name = wc.frames().frame(frame).name() + "Geo";
  instance.X_frame_geometry = X_frame_geometry;
  instance.geometry = std::move(geometry);
  wc.objectOf(frame).collision.push_back(std::move(instance));
}

/// An exact-name Exclude rule.
inline rw::models::ProximityRule exclude(const std::string& a, const std::string& b) {
  return rw::models::ProximityRule{a, b, false};
}

/// An Include rule.
inline rw::models::ProximityRule include(const std::string& a, const std::string& b) {
  return rw::models::ProximityRule{a, b, true};
}

/// RobWork's DistanceTest idea: four movable frames chained 1 m apart along x, each relative to
/// the previous one: F1 sphere r 0.2, F2 box 0.4, F3 sphere r 0.1, F4 box 0.2. The parent-child
/// pairs are excluded, leaving (F1,F3), (F1,F4), (F2,F4).
struct ChainScene {
  /// The workcell.
  std::unique_ptr<WorkCell> wc;
  /// F1..F4.
  std::array<FrameId, 4> f;
};

/// Builds the chain scene.
inline ChainScene makeChainScene() {
  ChainScene s;
  s.wc = std::make_unique<WorkCell>("DistanceTest");
  WorkCell& wc = *s.wc;
  FrameId parent = rw::kinematics::FrameTree::kWorld;
  for (std::size_t i = 0; i < 4; ++i) {
    const Transform3D X = i == 0 ? Transform3D::Identity() : pose({1, 0, 0});
    s.f[i] = addFrame(wc, "F" + std::to_string(i + 1), parent, FrameType::kMovable, X);
    parent = s.f[i];
  }
  using rw::geometry::Geometry;
  addGeometry(wc, s.f[0], Geometry::sphere(0.2));
  addGeometry(wc, s.f[1], Geometry::box(0.4, 0.4, 0.4));
  addGeometry(wc, s.f[2], Geometry::sphere(0.1));
  addGeometry(wc, s.f[3], Geometry::box(0.2, 0.2, 0.2));
  wc.proximitySetup().rules = {exclude("F1", "F2"), exclude("F2", "F3"), exclude("F3", "F4")};
  return s;
}

}  // namespace rw::proximity::test
