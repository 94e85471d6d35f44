#include "visgrab/generator/placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rw/common/strings.hpp"
#include "rw/proximity/convex_shape.hpp"
#include "rw/proximity/gjk.hpp"

namespace visgrab::generator {

namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

constexpr double kDeg = std::numbers::pi / 180.0;

std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

Transform3D turnedAboutZ(const Transform3D& X, double yaw) {
  return Transform3D(Eigen::AngleAxisd(yaw, Vector3D::UnitZ())) * X;
}

// The model at resting pose `pose`, turned by `yaw` about the table's z axis and moved so that
// its collision bounding box is centred on (x, y) and its lowest point touches z = 0.
Transform3D rest(const objects::ObjectModel& model, const objects::RestingPose& pose, double yaw,
                 double x, double y) {
  Transform3D X = turnedAboutZ(pose.X_TO, yaw);
  const auto [xlo, xhi] = extentAlong(model, X, Vector3D::UnitX());
  const auto [ylo, yhi] = extentAlong(model, X, Vector3D::UnitY());
  const auto [zlo, zhi] = extentAlong(model, X, Vector3D::UnitZ());
  (void)zhi;
  X.pretranslate(Vector3D(x - 0.5 * (xlo + xhi), y - 0.5 * (ylo + yhi), -zlo));
  return X;
}

const objects::RestingPose& standingPose(const objects::ObjectModel& model) {
  for (const auto& p : model.restingPoses) {
    if (!p.lying) return p;
  }
  throw std::invalid_argument("object " + model.name + " has no standing resting pose");
}

std::vector<const objects::RestingPose*> lyingPoses(const objects::ObjectModel& model) {
  std::vector<const objects::RestingPose*> out;
  for (const auto& p : model.restingPoses) {
    if (p.lying) out.push_back(&p);
  }
  if (out.empty()) throw std::invalid_argument("object " + model.name + " has no lying pose");
  return out;
}

}  // namespace

rw::proximity::ConvexShape convexShapeOf(const objects::CollisionPiece& piece) {
  const auto& g = *piece.geometry;
  const auto& p = g.parameters();
  switch (g.type()) {
    case rw::geometry::GeometryType::kCylinder:
      return rw::proximity::ConvexShape::cylinder(p[0], p[1] / 2.0);
    case rw::geometry::GeometryType::kFrustum:
      return rw::proximity::ConvexShape::frustum(p[0], p[1], p[2] / 2.0);
    default:
      return rw::proximity::ConvexShape::hull(g.triangles().vertices);
  }
}

double distanceBetween(const objects::ObjectModel& a, const Transform3D& X_TA,
                       const objects::ObjectModel& b, const Transform3D& X_TB) {
  const Transform3D X_AB = X_TA.inverse() * X_TB;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& pa : a.collision) {
    const auto shapeA = convexShapeOf(pa);
    for (const auto& pb : b.collision) {
      const Transform3D X_GaGb = pa.X_OG.inverse() * X_AB * pb.X_OG;
      best = std::min(best, rw::proximity::gjkDistance(shapeA, convexShapeOf(pb), X_GaGb).distance);
    }
  }
  return best;
}

std::string sceneIdOf(const database::SceneConditions& scene,
                      const std::vector<const objects::ObjectModel*>& models) {
  std::string subject;
  for (const auto* model : models) subject += (subject.empty() ? "" : "_") + model->name;
  const std::string pose = std::to_string(scene.pose);
  return std::string(database::toString(scene.texture)) + "/" +
         std::string(database::toString(scene.kind)) + "/" + subject + "/" +
         (pose.size() < 2 ? "0" : "") + pose;
}

Random::Random(std::uint64_t seed, std::string_view key) : state_(mix(seed)) {
  // FNV-1a of the key, mixed into the seed.
  state_ = mix(state_ ^ rw::common::fnv1a(key));
}

std::uint64_t Random::next() {
  state_ += 0x9e3779b97f4a7c15ULL;
  return mix(state_);
}

double Random::uniform(double lo, double hi) {
  const double u = static_cast<double>(next() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * u;
}

double Random::normal() {
  const double u1 = (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53;
  const double u2 = static_cast<double>(next() >> 11) * 0x1.0p-53;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::pair<double, double> extentAlong(const objects::ObjectModel& model, const Transform3D& X_TO,
                                      const Vector3D& d) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  const Vector3D dO = X_TO.linear().transpose() * d;
  const double offset = X_TO.translation().dot(d);
  for (const auto& piece : model.collision) {
    for (const Vector3D& v : piece.triangles->vertices) {
      const double s = v.dot(dO) + offset;
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  return {lo, hi};
}

Placement placeObjects(const database::SceneConditions& scene,
                       const std::vector<const objects::ObjectModel*>& models, std::uint64_t seed,
                       int attempt, const PlacementOptions& options) {
  if (models.size() != scene.objects.size() || models.empty() ||
      std::any_of(models.begin(), models.end(), [](const auto* m) { return m == nullptr; })) {
    throw std::invalid_argument("placeObjects: one model per object of the scene is needed");
  }
  Random random(seed, sceneIdOf(scene, models) + "#" + std::to_string(attempt));
  const int k = scene.pose;
  Placement placement;
  const double x = random.uniform(-options.spread, options.spread);
  const double y = random.uniform(-options.spread, options.spread);
  if (scene.kind == database::SceneKind::kSingle) {
    const objects::ObjectModel& m = *models[0];
    if (k <= 4) {
      const double yaw = (k - 1) * 90.0 * kDeg + random.uniform(-20.0, 20.0) * kDeg;
      placement.X_TO.push_back(rest(m, standingPose(m), yaw, x, y));
    } else {
      const auto lying = lyingPoses(m);
      const auto& pose = *lying[static_cast<std::size_t>(k - 5) % lying.size()];
      const double yaw = (k - 5) * 45.0 * kDeg + random.uniform(-15.0, 15.0) * kDeg;
      placement.X_TO.push_back(rest(m, pose, yaw, x, y));
    }
    return placement;
  }
  // A pair: both standing, side by side along direction `dir` (turning with the placement).
  const objects::ObjectModel& a = *models[0];
  const objects::ObjectModel& b = *models[1];
  const double angle = ((k - 1) % 4) * 45.0 * kDeg + random.uniform(-10.0, 10.0) * kDeg;
  const Vector3D dir(std::cos(angle), std::sin(angle), 0.0);
  const double gap =
      k <= 4 ? random.uniform(options.apartGapMin, options.apartGapMax) : options.closeGap;
  Transform3D X_a = rest(a, standingPose(a), random.uniform(0.0, 360.0) * kDeg, 0.0, 0.0);
  Transform3D X_b = rest(b, standingPose(b), random.uniform(0.0, 360.0) * kDeg, 0.0, 0.0);
  const double aHigh = extentAlong(a, X_a, dir).second;
  const double bLow = extentAlong(b, X_b, dir).first;
  // Move b along dir so that its extent starts `gap` beyond a's, then centre the pair.
  double shift = aHigh + gap - bLow;
  X_b.pretranslate(shift * dir);
  if (k > 4) {
    // Close: slide b back along dir until the true distance is the gap (a step along dir
    // shortens the distance by at most its length, so this never makes them overlap).
    for (int i = 0; i < 50; ++i) {
      const double excess = distanceBetween(a, X_a, b, X_b) - gap;
      if (excess < 1e-5) break;
      X_b.pretranslate(-excess * dir);
      shift -= excess;
    }
  }
  const Vector3D centre = 0.5 * shift * dir;
  X_a.pretranslate(Vector3D(x, y, 0.0) - centre);
  X_b.pretranslate(Vector3D(x, y, 0.0) - centre);
  placement.X_TO = {X_a, X_b};
  return placement;
}

}  // namespace visgrab::generator
