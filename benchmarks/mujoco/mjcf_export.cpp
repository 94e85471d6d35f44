#include "mujoco/mjcf_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "rw/common/strings.hpp"
#include "rw/geometry/geometry.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/proximity/proximity_filter.hpp"

namespace visgrab::mujoco {

namespace {

using rw::kinematics::FrameId;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::dynamics::BodyId;
using rwsim::dynamics::BodyKind;
using rwsim::dynamics::DynamicWorkCell;

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

struct Geom {
  std::string name;
  FrameId frame;
};

class Exporter {
 public:
  Exporter(const DynamicWorkCell& dwc, const MjcfOptions& options)
      : dwc_(dwc), wc_(dwc.workcell()), options_(options), X_W_(posesAtZero(wc_)) {}

  MjcfModel run();

 private:
  const Transform3D& world(FrameId f) const { return X_W_[static_cast<std::size_t>(f.index)]; }
  BodyId parentBody(std::size_t b) const;
  void writeBody(std::size_t b, int depth);
  void writeGeoms(std::size_t b, const std::string& indent);
  void writeContactPairs();
  void writeActuatorsAndEqualities();

  const DynamicWorkCell& dwc_;
  const rw::models::WorkCell& wc_;
  const MjcfOptions& options_;
  std::vector<Transform3D> X_W_;
  std::vector<std::vector<std::size_t>> children_;  // per body; the last entry is the world
  std::vector<std::vector<Geom>> geoms_;            // per body
  std::set<std::string> geomNames_;
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

void Exporter::writeGeoms(std::size_t b, const std::string& indent) {
  const auto& body = dwc_.bodies()[b];
  const Transform3D X_body_W = world(body.frame).inverse();
  for (const FrameId f : body.geometryFrames) {
    const rw::models::Object* object = wc_.findObject(f);
    if (object == nullptr) continue;
    const std::string& frameName = wc_.frames().frame(f).name();
    for (const auto& g : object->collision) {
      const auto& p = g.geometry->parameters();
      std::string shape;
      switch (g.geometry->type()) {
        case rw::geometry::GeometryType::kBox:
          shape = "type=\"box\" size=\"" + vec(Vector3D(p[0], p[1], p[2]) / 2.0) + "\"";
          break;
        case rw::geometry::GeometryType::kSphere:
          shape = "type=\"sphere\" size=\"" + num(p[0]) + "\"";
          break;
        case rw::geometry::GeometryType::kCylinder:
          shape = "type=\"cylinder\" size=\"" + num(p[0]) + " " + num(p[1] / 2.0) + "\"";
          break;
        case rw::geometry::GeometryType::kPlane:
          if (body.kind != BodyKind::kFixed) {
            throw std::invalid_argument("frame '" + frameName + "': Plane '" + g.name +
                                        "' on a moving body (" + body.name +
                                        "); MJCF planes must be static");
          }
          shape = "type=\"plane\" size=\"0 0 1\"";
          break;
        default: {
          const std::string file = g.geometry->sourceFile().empty()
                                       ? std::string()
                                       : " (" + g.geometry->sourceFile() + ")";
          throw std::invalid_argument(
              "frame '" + frameName + "': cannot export " +
              rw::geometry::geometryTypeName(g.geometry->type()) + " '" + g.name + "'" + file +
              " to MJCF; only Box, Sphere, Cylinder and Plane (on a fixed body) are supported");
        }
      }
      std::string name = frameName + "/" + g.name;
      for (int i = 2; geomNames_.count(name) > 0; ++i) {
        name = frameName + "/" + g.name + "#" + std::to_string(i);
      }
      geomNames_.insert(name);
      geoms_[b].push_back(Geom{name, f});
      out_ += indent + "<geom name=\"" + attr(name) + "\" " + shape + " " +
              poseAttrs(X_body_W * world(f) * g.X_frame_geometry) + "/>\n";
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
      out_ += in + "<joint name=\"" + attr(body.name) + "\" type=\"" +
              (frame.type() == rw::kinematics::FrameType::kRevolute ? "hinge" : "slide") +
              "\" axis=\"0 0 1\" limited=\"" + (limited ? "true" : "false") + "\"" +
              (limited ? " range=\"" + num(lim.lower) + " " + num(lim.upper) + "\"" : "") + "/>\n";
    } else {
      out_ += in + "<freejoint name=\"" + attr(body.name) + "\"/>\n";
    }
  } else if (body.kind == BodyKind::kKinematic) {
    // The kinematic body moves along world x, y and z, driven by stiff velocity servos.
    const double m = options_.kinematicMass;
    out_ += in + "<inertial pos=\"0 0 0\" mass=\"" + num(m) + "\" diaginertia=\"" +
            vec(Vector3D::Constant(m * 1e-3)) + "\"/>\n";
    const Eigen::Matrix3d R_body_W = world(body.frame).linear().transpose();
    const char* axes[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
      const std::string name = body.name + ":" + axes[i];
      model_.slideJoints[b].push_back(name);
      out_ += in + "<joint name=\"" + attr(name) + "\" type=\"slide\" limited=\"false\" axis=\"" +
              vec(R_body_W.col(i)) + "\"/>\n";
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
          out_ += "    <pair geom1=\"" + attr(a.name) + "\" geom2=\"" + attr(b.name) +
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
  for (std::size_t b = 0; b < dwc_.bodies().size(); ++b) {
    for (const std::string& slide : model_.slideJoints[b]) {
      out_ += "    <motor name=\"" + attr(slide) + "\" joint=\"" + attr(slide) +
              "\" ctrllimited=\"false\"/>\n";
    }
  }
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
      out_ += "    <motor name=\"" + attr(f.name()) + "\" joint=\"" + attr(f.name()) +
              "\" ctrllimited=\"false\" forcelimited=\"true\" forcerange=\"" + num(-limit) + " " +
              num(limit) + "\"/>\n";
    }
  }
  out_ += "  </actuator>\n";
  if (!equalities.empty()) out_ += "  <equality>\n" + equalities + "  </equality>\n";
}

MjcfModel Exporter::run() {
  const auto& bodies = dwc_.bodies();
  model_.bodyNames.resize(bodies.size());
  model_.slideJoints.resize(bodies.size());
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
  const Vector3D& g = dwc_.gravity();
  out_ = "<mujoco model=\"" + attr(wc_.name()) + "\">\n";
  out_ += "  <!-- Exported by dwc2mjcf from " + attr(dwc_.fileName()) + " -->\n";
  out_ += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  out_ += "  <option timestep=\"" + num(options_.timeStep) + "\" gravity=\"" + vec(g) +
          "\" integrator=\"implicit\" cone=\"elliptic\" impratio=\"" + num(options_.impratio) +
          "\" solver=\"Newton\"/>\n";
  out_ += "  <default>\n    <geom contype=\"0\" conaffinity=\"0\"/>\n  </default>\n";
  out_ += "  <worldbody>\n";
  for (const std::size_t b : children_[bodies.size()]) writeBody(b, 2);
  out_ += "  </worldbody>\n";
  writeContactPairs();
  writeActuatorsAndEqualities();
  out_ += "</mujoco>\n";
  model_.xml = std::move(out_);
  return std::move(model_);
}

}  // namespace

MjcfModel exportMjcf(const DynamicWorkCell& dwc, const MjcfOptions& options) {
  return Exporter(dwc, options).run();
}

}  // namespace visgrab::mujoco
