#include "rwsim/mujoco/mjcf_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/common/strings.hpp"
#include "rw/geometry/geometry.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/proximity/proximity_filter.hpp"

namespace rwsim::mujoco {

namespace {

using dynamics::BodyId;
using dynamics::BodyKind;
using dynamics::DynamicWorkCell;
using rw::geometry::GeometryType;
using rw::geometry::TriMesh;
using rw::kinematics::FrameId;
using rw::math::Transform3D;
using rw::math::Vector3D;

// Round-trip precision; rounding noise below 1e-15 (poses in m, inertias about 1e-5 kg m^2)
// written as 0 so the file stays readable.
std::string num(double v) {
  if (std::abs(v) < 1e-15) return "0";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string vec(const Vector3D& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

// MJCF attribute text: XML-escaped.
std::string attr(const std::string& s) { return rw::common::escapeXml(s); }

// pos="..." quat="..." of X (MuJoCo's quaternion order w x y z).
std::string poseAttrs(const Transform3D& X) {
  const Eigen::Quaterniond q(X.linear());
  return "pos=\"" + vec(X.translation()) + "\" quat=\"" + num(q.w()) + " " + num(q.x()) + " " +
         num(q.y()) + " " + num(q.z()) + "\"";
}

// World poses of all frames with every joint at 0 (dependent ones too) and the other frames as
// in the default state.
std::vector<Transform3D> posesAtZero(const rw::models::WorkCell& wc) {
  const auto& tree = wc.frames();
  const rw::kinematics::State state = wc.defaultState();
  std::vector<Transform3D> X_W(tree.size(), Transform3D::Identity());
  for (const auto& f : tree.frames()) {
    const FrameId parent = state.parentOf(f.id());
    if (!parent.valid()) continue;
    const Transform3D local = f.isJoint() ? f.fixedTransform() : f.localTransform(state);
    X_W[static_cast<std::size_t>(f.id().index)] =
        X_W[static_cast<std::size_t>(parent.index)] * local;
  }
  return X_W;
}

// A cuboid: pose of its centre in the mesh's frame and half edge lengths.
struct Cuboid {
  Transform3D X_mesh_box = Transform3D::Identity();
  Vector3D halfSize = Vector3D::Zero();
};

// The mesh's distinct vertices (the loaders repeat them per triangle).
std::vector<Vector3D> distinctVertices(const TriMesh& mesh) {
  std::vector<Vector3D> out;
  for (const Vector3D& v : mesh.vertices) {
    const bool seen = std::any_of(out.begin(), out.end(),
                                  [&](const Vector3D& u) { return (u - v).norm() < 1e-9; });
    if (!seen) out.push_back(v);
  }
  return out;
}

// True when every corner is corners[0] plus a sum of some of the edges a, b, c.
bool spansCorners(const std::vector<Vector3D>& corners, const Vector3D& a, const Vector3D& b,
                  const Vector3D& c) {
  for (const Vector3D& p : corners) {
    const Vector3D d = p - corners[0];
    const Vector3D t(d.dot(a) / a.squaredNorm(), d.dot(b) / b.squaredNorm(),
                     d.dot(c) / c.squaredNorm());
    for (int k = 0; k < 3; ++k) {
      if (std::min(std::abs(t[k]), std::abs(t[k] - 1.0)) > 1e-9) return false;
    }
  }
  return true;
}

// The cuboid a convex mesh is, if it is one: eight corners, three of the edges from the first
// corner to the others orthogonal, and every corner the first plus a sum of some of them.
std::optional<Cuboid> cuboidOf(const std::vector<Vector3D>& corners) {
  if (corners.size() != 8) return std::nullopt;
  std::vector<Vector3D> edges;
  for (std::size_t i = 1; i < corners.size(); ++i) edges.push_back(corners[i] - corners[0]);
  const auto orthogonal = [](const Vector3D& u, const Vector3D& v) {
    return std::abs(u.dot(v)) <= 1e-9 * u.norm() * v.norm();
  };
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      for (std::size_t k = j + 1; k < edges.size(); ++k) {
        const Vector3D& a = edges[i];
        const Vector3D& b = edges[j];
        const Vector3D& c = edges[k];
        if (!orthogonal(a, b) || !orthogonal(a, c) || !orthogonal(b, c)) continue;
        if (!spansCorners(corners, a, b, c)) continue;
        Cuboid box;
        Eigen::Matrix3d R;
        R.col(0) = a.normalized();
        R.col(1) = b.normalized();
        R.col(2) = R.col(0).cross(R.col(1));
        box.X_mesh_box.linear() = R;
        box.X_mesh_box.translation() = corners[0] + 0.5 * (a + b + c);
        box.halfSize = Vector3D(a.norm(), b.norm(), c.norm()) / 2.0;
        return box;
      }
    }
  }
  return std::nullopt;
}

// Volume enclosed by a closed, outward-wound triangle mesh (divergence theorem), m^3.
double enclosedVolume(const TriMesh& mesh) {
  double six = 0.0;
  for (const auto& t : mesh.triangles) {
    six += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return six / 6.0;
}

// The vertices of a frustum's hull: `segments`-gons inscribed in its end circles (a point where
// a radius is 0), axis z from -h/2 to +h/2 (rw::geometry's convention).
std::vector<Vector3D> frustumVertices(double bottomRadius, double topRadius, double height,
                                      int segments) {
  std::vector<Vector3D> out;
  for (const auto& [r, z] : {std::pair{bottomRadius, -height / 2.0}, {topRadius, height / 2.0}}) {
    if (r <= 0.0) {
      out.emplace_back(0.0, 0.0, z);
      continue;
    }
    for (int k = 0; k < segments; ++k) {
      const double a = 2.0 * std::numbers::pi * k / segments;
      out.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  return out;
}

struct Geom {
  std::string name;
  FrameId frame;
  /// Exported as an MJCF box.
  bool box = false;
  /// For a box on a fixed body with a face straight up: the plane of that face, which stands in
  /// for the box in its pairs with boxes (see writeGeoms).
  std::string topPlane;
};

class Exporter {
 public:
  Exporter(const DynamicWorkCell& dwc, const MujocoOptions& options)
      : dwc_(dwc), wc_(dwc.workcell()), options_(options), X_W_(posesAtZero(wc_)) {}

  MjcfModel run();

 private:
  const Transform3D& world(FrameId f) const { return X_W_[static_cast<std::size_t>(f.index)]; }
  BodyId parentBody(std::size_t b) const;
  void writeBody(std::size_t b, int depth);
  void writeGeoms(std::size_t b, const std::string& indent);
  std::string shapeOf(const dynamics::Body& body, const std::string& frameName,
                      const rw::models::GeometryInstance& g, Transform3D& X_geom_shape);
  std::string meshAsset(const std::vector<Vector3D>& vertices);
  void writeContactPairs();
  void writeActuatorsAndEqualities();

  const DynamicWorkCell& dwc_;
  const rw::models::WorkCell& wc_;
  const MujocoOptions& options_;
  std::vector<Transform3D> X_W_;
  std::vector<std::vector<std::size_t>> children_;  // per body; the last entry is the world
  std::vector<std::vector<Geom>> geoms_;            // per body
  std::set<std::string> geomNames_;
  std::string assets_;
  int meshes_ = 0;
  std::string out_;
  MjcfModel model_;
};

// The MJCF parent of a body: a device link hangs below the body above its joint, every other
// body below the world (none).
BodyId Exporter::parentBody(std::size_t b) const {
  const auto& body = dwc_.bodies()[b];
  if (!body.device.valid() || dwc_.device(body.device).baseBody == BodyId(b)) return BodyId();
  return dwc_.bodyAbove(body.frame);
}

std::string Exporter::meshAsset(const std::vector<Vector3D>& vertices) {
  const std::string name = "mesh" + std::to_string(meshes_++);
  assets_ += "    <mesh name=\"" + name + "\" vertex=\"";
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    assets_ += (i == 0 ? "" : " ") + vec(vertices[i]);
  }
  assets_ += "\"/>\n";
  return name;
}

// The geom attributes (type, size or mesh) of one collision piece; X_geom_shape is where the
// MJCF shape sits in the piece's frame (a cuboid mesh's box centre).
std::string Exporter::shapeOf(const dynamics::Body& body, const std::string& frameName,
                              const rw::models::GeometryInstance& g, Transform3D& X_geom_shape) {
  const auto& p = g.geometry->parameters();
  const std::string type = rw::geometry::geometryTypeName(g.geometry->type());
  const std::string source =
      g.geometry->sourceFile().empty() ? std::string() : " (" + g.geometry->sourceFile() + ")";
  const auto refuse = [&](const std::string& why) {
    return std::invalid_argument("frame '" + frameName + "' (body " + body.name + "): " + type +
                                 " '" + g.name + "'" + source + ": " + why);
  };
  X_geom_shape = Transform3D::Identity();
  switch (g.geometry->type()) {
    case GeometryType::kBox:
      return "type=\"box\" size=\"" + vec(Vector3D(p[0], p[1], p[2]) / 2.0) + "\"";
    case GeometryType::kSphere:
      return "type=\"sphere\" size=\"" + num(p[0]) + "\"";
    case GeometryType::kCylinder:
      return "type=\"cylinder\" size=\"" + num(p[0]) + " " + num(p[1] / 2.0) + "\"";
    case GeometryType::kCone:
      return "type=\"mesh\" mesh=\"" +
             meshAsset(frustumVertices(0.0, p[0], p[1], options_.roundSegments)) + "\"";
    case GeometryType::kFrustum:
      return "type=\"mesh\" mesh=\"" +
             meshAsset(frustumVertices(p[0], p[1], p[2], options_.roundSegments)) + "\"";
    case GeometryType::kPlane:
      if (body.kind != BodyKind::kFixed) {
        throw refuse("a plane on a moving body cannot be exported; MJCF planes must be static");
      }
      return "type=\"plane\" size=\"0 0 1\"";
    case GeometryType::kTube:
      throw refuse(
          "a tube is not convex and MJCF has no tube; model it as convex pieces (e.g. boxes "
          "around the ring)");
    case GeometryType::kMesh: {
      if (!g.geometry->isConvex()) {
        throw refuse(
            "the mesh is not convex and MuJoCo would collide with its convex hull; split it into "
            "convex pieces, one collision geometry each");
      }
      const TriMesh& mesh = g.geometry->triangles();
      const Vector3D size = g.geometry->bounds().max - g.geometry->bounds().min;
      if (!(enclosedVolume(mesh) > 1e-6 * std::pow(size.norm(), 3))) {
        throw refuse("the mesh encloses no volume (flat or open); MuJoCo needs a solid hull");
      }
      const std::vector<Vector3D> corners = distinctVertices(mesh);
      if (const auto box = cuboidOf(corners)) {
        X_geom_shape = box->X_mesh_box;
        return "type=\"box\" size=\"" + vec(box->halfSize) + "\"";
      }
      return "type=\"mesh\" mesh=\"" + meshAsset(corners) + "\"";
    }
  }
  throw refuse("unknown geometry type");
}

void Exporter::writeGeoms(std::size_t b, const std::string& indent) {
  const auto& body = dwc_.bodies()[b];
  const Transform3D X_body_W = world(body.frame).inverse();
  for (const FrameId f : body.geometryFrames) {
    const rw::models::Object* object = wc_.findObject(f);
    if (object == nullptr) continue;
    const std::string& frameName = wc_.frames().frame(f).name();
    for (const auto& g : object->collision) {
      Transform3D X_geom_shape;
      const std::string shape = shapeOf(body, frameName, g, X_geom_shape);
      std::string name = frameName + "/" + g.name;
      for (int i = 2; geomNames_.count(name) > 0; ++i) {
        name = frameName + "/" + g.name + "#" + std::to_string(i);
      }
      geomNames_.insert(name);
      Geom geom{name, f, shape.starts_with("type=\"box\""), {}};
      const Transform3D X_body_geom = X_body_W * world(f) * g.X_frame_geometry * X_geom_shape;
      out_ += indent + "<geom name=\"" + attr(name) + "\" " + shape + " " + poseAttrs(X_body_geom) +
              "/>\n";
      // MuJoCo 2.2.2's box-box collider can return a phantom contact as deep as a box's width
      // for boxes resting face to face (google-deepmind/mujoco#3476): an object box standing on
      // the table box is shot away at ~90 m/s. A fixed box with a face straight up (the table)
      // therefore meets other boxes through the plane of that face (box-plane is exact); the
      // plane is unbounded, so a box pushed past the table's edge would not fall (never in a
      // grasp trial; docs/validation.md).
      const Transform3D X_W_geom = world(body.frame) * X_body_geom;
      if (g.geometry->type() == GeometryType::kBox && body.kind == BodyKind::kFixed &&
          X_W_geom.linear().col(2).z() > 1.0 - 1e-9) {
        Transform3D X_body_plane = X_body_geom;
        X_body_plane.translation() +=
            X_body_geom.linear().col(2) * (g.geometry->parameters()[2] / 2.0);
        geom.topPlane = name + "#top";
        geomNames_.insert(geom.topPlane);
        out_ += indent + "<geom name=\"" + attr(geom.topPlane) +
                "\" type=\"plane\" size=\"0 0 1\" " + poseAttrs(X_body_plane) + "/>\n";
      }
      geoms_[b].push_back(std::move(geom));
    }
  }
}

void Exporter::writeBody(std::size_t b, int depth) {
  const auto& body = dwc_.bodies()[b];
  const std::string indent(static_cast<std::size_t>(2 * depth), ' ');
  const BodyId parent = parentBody(b);
  const Transform3D X_parent_body =
      (parent.valid() ? world(dwc_.body(parent).frame).inverse() : Transform3D::Identity()) *
      world(body.frame);
  out_ += indent + "<body name=\"" + attr(body.name) + "\" " + poseAttrs(X_parent_body) + ">\n";
  const std::string in = indent + "  ";
  const auto& frame = wc_.frames().frame(body.frame);
  if (body.kind == BodyKind::kRigid) {
    const auto& I = body.mass.inertia;
    out_ += in + "<inertial pos=\"" + vec(body.mass.cog) + "\" mass=\"" + num(body.mass.mass) +
            "\" fullinertia=\"" + num(I(0, 0)) + " " + num(I(1, 1)) + " " + num(I(2, 2)) + " " +
            num(I(0, 1)) + " " + num(I(0, 2)) + " " + num(I(1, 2)) + "\"/>\n";
    if (parent.valid() || (body.device.valid() && frame.isJoint())) {
      if (!frame.isJoint()) {
        throw std::invalid_argument("body '" + body.name +
                                    "': a device link must be on a joint frame");
      }
      const auto& lim = frame.limits();
      const bool limited = std::isfinite(lim.lower) && std::isfinite(lim.upper);
      const bool revolute = frame.type() == rw::kinematics::FrameType::kRevolute;
      out_ += in + "<joint name=\"" + attr(body.name) + "\" type=\"" +
              (revolute ? "hinge" : "slide") + "\" axis=\"0 0 1\" armature=\"" +
              num(revolute ? options_.motorArmature : options_.prismaticMotorArmature) +
              "\" limited=\"" + (limited ? "true" : "false") + "\"" +
              (limited ? " range=\"" + num(lim.lower) + " " + num(lim.upper) + "\"" : "") + "/>\n";
    } else {
      out_ += in + "<freejoint name=\"" + attr(body.name) + "\"/>\n";
    }
  } else if (body.kind == BodyKind::kKinematic) {
    if (parent.valid()) {
      throw std::invalid_argument("body '" + body.name +
                                  "': a kinematic device link cannot be exported");
    }
    // Slides along and hinges about the body frame's axes at its origin; the engine places the
    // body by its pose in the model and moves it by writing these joints' velocities.
    const double m = options_.kinematicMass;
    out_ += in + "<inertial pos=\"0 0 0\" mass=\"" + num(m) + "\" diaginertia=\"" +
            vec(Vector3D::Constant(m * 1e-3)) + "\"/>\n";
    const char* names[] = {":x", ":y", ":z", ":rx", ":ry", ":rz"};
    const char* axes[] = {"1 0 0", "0 1 0", "0 0 1"};
    for (int i = 0; i < 6; ++i) {
      const std::string name = body.name + names[i];
      model_.kinematicJoints[b].push_back(name);
      out_ += in + "<joint name=\"" + attr(name) + "\" type=\"" + (i < 3 ? "slide" : "hinge") +
              "\" pos=\"0 0 0\" axis=\"" + axes[i % 3] + "\" limited=\"false\" armature=\"" +
              num(options_.kinematicArmature) + "\"/>\n";
    }
  }
  writeGeoms(b, in);
  for (const std::size_t c : children_[b]) writeBody(c, depth + 1);
  out_ += indent + "</body>\n";
}

void Exporter::writeContactPairs() {
  const rw::proximity::ProximityFilter filter(wc_);
  const auto excluded = rwsim::dynamics::jointConnectedBodyPairs(dwc_);
  const auto& bodies = dwc_.bodies();
  const std::string solref =
      num(options_.solrefTimeConstant) + " " + num(options_.solrefDampingRatio);
  out_ += "  <contact>\n";
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      if (bodies[i].kind != BodyKind::kRigid && bodies[j].kind != BodyKind::kRigid) continue;
      if (std::find(excluded.begin(), excluded.end(), std::make_pair(BodyId(i), BodyId(j))) !=
          excluded.end()) {
        continue;
      }
      const double mu = dwc_.materials().mu(bodies[i].material, bodies[j].material);
      for (const Geom& a : geoms_[i]) {
        for (const Geom& b : geoms_[j]) {
          if (a.frame == b.frame || !filter.contains(a.frame, b.frame)) continue;
          // A box against a fixed box's top face: through its plane (see writeGeoms).
          const std::string& nameA = a.box && b.box && !a.topPlane.empty() ? a.topPlane : a.name;
          const std::string& nameB = a.box && b.box && !b.topPlane.empty() ? b.topPlane : b.name;
          out_ += "    <pair geom1=\"" + attr(nameA) + "\" geom2=\"" + attr(nameB) +
                  "\" condim=\"3\" friction=\"" + num(mu) + " " + num(mu) +
                  " 0.005 0.0001 0.0001\" solref=\"" + solref + "\"/>\n";
        }
      }
    }
  }
  out_ += "  </contact>\n";
}

void Exporter::writeActuatorsAndEqualities() {
  const auto& tree = wc_.frames();
  std::string equalities;
  out_ += "  <actuator>\n";
  for (const auto& rd : dwc_.devices()) {
    auto& names = model_.activeJoints.emplace_back();
    const auto& joints = rd.device->joints();
    for (std::size_t k = 0; k < joints.size(); ++k) {
      const auto& f = tree.frame(joints[k]);
      if (!rd.linkBodies[k].valid()) {
        throw std::invalid_argument("joint '" + f.name() + "' of device '" + rd.device->name() +
                                    "' has no rigid link body; MJCF needs one per joint");
      }
      if (f.isDependent()) {
        const auto& dep = *f.dependency();
        equalities += "    <joint joint1=\"" + attr(f.name()) + "\" joint2=\"" +
                      attr(tree.frame(dep.owner).name()) + "\" polycoef=\"" + num(dep.offset) +
                      " " + num(dep.gain) + " 0 0 0\" solref=\"" +
                      num(options_.solrefTimeConstant) + " " + num(options_.solrefDampingRatio) +
                      "\"/>\n";
        continue;
      }
      if (!f.isActiveJoint()) continue;
      names.push_back(f.name());
      const double limit = rd.forceLimits[k];
      const double gain = f.type() == rw::kinematics::FrameType::kRevolute
                              ? options_.motorGain
                              : options_.prismaticMotorGain;
      out_ += "    <velocity name=\"" + attr(f.name()) + "\" joint=\"" + attr(f.name()) +
              "\" kv=\"" + num(gain) +
              "\" ctrllimited=\"false\" forcelimited=\"true\" forcerange=\"" + num(-limit) + " " +
              num(limit) + "\"/>\n";
    }
  }
  out_ += "  </actuator>\n";
  if (!equalities.empty()) out_ += "  <equality>\n" + equalities + "  </equality>\n";
}

MjcfModel Exporter::run() {
  const auto& bodies = dwc_.bodies();
  if (!dwc_.constraints().empty()) {
    throw std::invalid_argument("constraint '" + dwc_.constraints().front().name +
                                "': dwc constraints are not exported to MJCF");
  }
  for (const auto& rd : dwc_.devices()) {
    if (!rd.loopClosures.empty()) {
      throw std::invalid_argument("device '" + rd.device->name() +
                                  "': parallel devices (loop closures) are not exported to MJCF");
    }
  }
  model_.bodyNames.resize(bodies.size());
  model_.kinematicJoints.resize(bodies.size());
  children_.assign(bodies.size() + 1, {});
  geoms_.assign(bodies.size(), {});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    model_.bodyNames[b] = bodies[b].name;
    const BodyId parent = parentBody(b);
    children_[parent.valid() ? parent.index() : bodies.size()].push_back(b);
  }
  for (const auto& object : wc_.objects()) {
    if (!object.collision.empty() && !dwc_.bodyOfFrame(object.frame).valid()) {
      model_.skippedFrames.push_back(wc_.frames().frame(object.frame).name());
    }
  }
  // The bodies first: they collect the mesh assets, which MJCF wants before them.
  out_ = "  <worldbody>\n";
  for (const std::size_t b : children_[bodies.size()]) writeBody(b, 2);
  out_ += "  </worldbody>\n";
  writeContactPairs();
  writeActuatorsAndEqualities();
  const Vector3D& g = dwc_.gravity();
  std::string head = "<mujoco model=\"" + attr(wc_.name()) + "\">\n";
  head += "  <!-- Exported by rwsim::mujoco::exportMjcf from " + attr(dwc_.fileName()) + " -->\n";
  head += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  head += "  <option timestep=\"" + num(options_.timeStep) + "\" gravity=\"" + vec(g) +
          "\" integrator=\"" + attr(options_.integrator) + "\" cone=\"" + attr(options_.cone) +
          "\" impratio=\"" + num(options_.impratio) + "\" solver=\"" + attr(options_.solver) +
          "\"/>\n";
  head += "  <default>\n    <geom contype=\"0\" conaffinity=\"0\"/>\n  </default>\n";
  if (!assets_.empty()) head += "  <asset>\n" + assets_ + "  </asset>\n";
  model_.xml = head + out_ + "</mujoco>\n";
  return std::move(model_);
}

}  // namespace

MjcfModel exportMjcf(const DynamicWorkCell& dwc, const MujocoOptions& options) {
  return Exporter(dwc, options).run();
}

}  // namespace rwsim::mujoco
