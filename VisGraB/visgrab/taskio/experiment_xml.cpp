#include "visgrab/taskio/experiment_xml.hpp"

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "rw/common/xml_attributes.hpp"
#include "visgrab/taskio/detail/common.hpp"

namespace visgrab::taskio {

using grasp::GraspKind;
using grasp::GraspRequest;
using rw::common::XmlElement;
using rw::math::Q;
using rw::math::Rotation3D;
using rw::math::Vector3D;

namespace {

/// Lengths in the experiment file are millimetres.
constexpr double kMillimetre = 1e-3;

/// Why one grasp is rejected, and where.
struct GraspError {
  const XmlElement* where;
  std::string message;
};

std::string trimmed(std::string_view text) { return std::string(rw::common::trimXmlSpace(text)); }

const XmlElement& required(const XmlElement& parent, std::string_view name) {
  if (const XmlElement* c = detail::child(parent, name)) return *c;
  throw GraspError{&parent, parent.describe() + ": missing <" + std::string(name) + ">"};
}

std::vector<double> numbers(const XmlElement& e, std::size_t count, std::string_view what) {
  std::vector<double> v;
  const std::string why = rw::common::parseNumbers(e.text, count, what, v);
  if (!why.empty()) throw GraspError{&e, e.describe() + ": " + why};
  return v;
}

Vector3D vector3(const XmlElement& e, double scale, std::string_view what) {
  const auto v = numbers(e, 3, what);
  return Vector3D(v[0], v[1], v[2]) * scale;
}

Vector3D direction(const XmlElement& e, std::string_view what) {
  const Vector3D d = vector3(e, 1.0, what);
  if (d.norm() < 1e-12) throw GraspError{&e, e.describe() + ": zero vector, expected a direction"};
  return d;
}

Q qVector(const XmlElement& e) {
  const auto v = numbers(e, 0, "");
  return Eigen::Map<const Q>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// q_open, q_closed, tau_max with the project's length rules.
struct Shape {
  Q open, close, tau;
};

Shape readShape(const XmlElement& parent) {
  Shape s;
  const XmlElement& open = required(parent, "qopen");
  const XmlElement& close = required(parent, "qclose");
  const XmlElement& tau = required(parent, "maxtau");
  s.open = qVector(open);
  s.close = qVector(close);
  s.tau = qVector(tau);
  if (s.open.size() == 0) throw GraspError{&open, "<qopen> is empty, expected joint values"};
  if (s.close.size() != s.open.size()) {
    throw GraspError{&close, "<qclose> has " + std::to_string(s.close.size()) +
                                 " values, expected as many as <qopen> (" +
                                 std::to_string(s.open.size()) + ")"};
  }
  if (s.tau.size() != 0 && s.tau.size() != s.open.size()) {
    throw GraspError{&tau, "<maxtau> has " + std::to_string(s.tau.size()) + " values, expected " +
                               std::to_string(s.open.size())};
  }
  return s;
}

rw::math::Transform3D readPose(const XmlElement& grasp) {
  const XmlElement& pose = required(grasp, "pose");
  const Vector3D p = vector3(required(pose, "position"), kMillimetre, "x y z in mm");
  Rotation3D R = Rotation3D::Identity();
  // The later of <quaternion> and <rotmatrix> wins, as in the original reader.
  for (const auto& c : pose.children) {
    const auto name = detail::localName(c.name);
    if (name == "quaternion") {
      const auto q = numbers(c, 4, "w x y z");
      std::string error;
      R = detail::quaternionRotation(q[0], q[1], q[2], q[3], error);
      if (!error.empty()) throw GraspError{&c, c.describe() + ": " + error};
    } else if (name == "rotmatrix") {
      const auto v = numbers(c, 9, "row-major 3x3 matrix");
      Rotation3D M;
      for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 3; ++k) M(r, k) = v[static_cast<std::size_t>(3 * r + k)];
      }
      const double error = detail::orthonormalityError(M);
      if (error > detail::kRotationTolerance || M.determinant() <= 0) {
        throw GraspError{&c, c.describe() +
                                 ": not a rotation matrix (largest entry of R^T R - I "
                                 "is " +
                                 detail::formatNumber(error) + ", determinant " +
                                 detail::formatNumber(M.determinant()) +
                                 "; expected an orthonormal matrix within 1e-3, determinant +1)"};
      }
      R = detail::nearestRotation(M);
    }
  }
  return rw::math::makeTransform(R, p);
}

class ExperimentReader {
 public:
  ExperimentReader(const std::string& file, GraspFileContents& out) : file_(file), out_(out) {}

  void read(const XmlElement& experiment) {
    std::string method;
    std::string scene;
    try {
      const std::string* id = experiment.attribute("id");
      if (id == nullptr || trimmed(*id).empty()) {
        throw GraspError{&experiment, "<experiment> has no id attribute; its grasps are skipped"};
      }
      method = trimmed(*id);
      const XmlElement& info = required(experiment, "sceneInfo");
      scene = trimmed(required(info, "sceneID").text);
      if (scene.empty())
        throw GraspError{&info,
                         "<sceneID> is empty; the experiment's grasps "
                         "are skipped"};
    } catch (const GraspError& e) {
      reject(e);
      return;
    }
    readPreshapes(experiment);
    std::map<std::string, int> ids;
    for (const auto& c : experiment.children) {
      const auto name = detail::localName(c.name);
      if (name != "grasp" && name != "preshapegrasp" && name != "contactgrasp") continue;
      try {
        GraspRequest r;
        r.sceneId = scene;
        r.method = method;
        r.sourceFile = file_;
        r.sourceLine = c.location.line;
        const std::string* id = c.attribute("id");
        if (id == nullptr || trimmed(*id).empty()) {
          throw GraspError{&c, c.describe() + ": missing required attribute \"id\""};
        }
        r.id = trimmed(*id);
        if (name == "grasp") {
          r.X_W_tcp = readPose(c);
          Shape s = readShape(c);
          r.qOpen = std::move(s.open);
          r.qClosed = std::move(s.close);
          r.tauMax = std::move(s.tau);
        } else if (name == "preshapegrasp") {
          r.X_W_tcp = readPose(c);
          const XmlElement& ref = required(c, "preshape");
          const std::string preshape = trimmed(ref.attributeOr("id", ""));
          const auto it = preshapes_.find(preshape);
          if (it == preshapes_.end()) {
            throw GraspError{&ref, "pre-shape \"" + preshape +
                                       "\" is not defined in the "
                                       "experiment's <gripper>"};
          }
          if (!it->second.error.empty()) {
            throw GraspError{&ref,
                             "pre-shape \"" + preshape + "\" is unusable: " + it->second.error};
          }
          r.qOpen = it->second.shape.open;
          r.qClosed = it->second.shape.close;
          r.tauMax = it->second.shape.tau;
          r.preshape = preshape;
        } else {
          r.kind = GraspKind::kContacts;
          for (const auto& k : c.children) {
            if (detail::localName(k.name) != "contact") continue;
            grasp::DesiredContact contact;
            contact.position = vector3(required(k, "pos"), kMillimetre, "x y z in mm");
            contact.direction = direction(required(k, "dir"), "push direction");
            r.contacts.push_back(contact);
          }
          if (r.contacts.size() < 2 || r.contacts.size() > 3) {
            throw GraspError{&c, c.describe() + ": " + std::to_string(r.contacts.size()) +
                                     " <contact> elements, expected 2 or 3"};
          }
          r.approach = direction(required(c, "approachVector"), "approach direction");
        }
        const auto [it, inserted] = ids.emplace(r.id, c.location.line);
        if (!inserted) {
          throw GraspError{&c, c.describe() + ": duplicate grasp id in experiment \"" + method +
                                   "\" (first on line " + std::to_string(it->second) + ")"};
        }
        out_.requests.push_back(std::move(r));
      } catch (const GraspError& e) {
        reject(e);
      }
    }
  }

 private:
  struct Preshape {
    Shape shape;
    std::string error;
  };

  void readPreshapes(const XmlElement& experiment) {
    const XmlElement* gripper = detail::child(experiment, "gripper");
    if (gripper == nullptr) return;  // only pre-shape grasps need it; they say so
    for (const auto& c : gripper->children) {
      if (detail::localName(c.name) != "preshape") continue;
      Preshape p;
      try {
        p.shape = readShape(c);
      } catch (const GraspError& e) {
        p.error = e.message + " (at line " + std::to_string(e.where->location.line) + ")";
      }
      preshapes_[trimmed(c.attributeOr("id", ""))] = std::move(p);  // later one wins
    }
  }

  void reject(const GraspError& e) {
    out_.rejected.push_back(
        detail::errorAt(file_, e.where->location.line, e.where->location.column, e.message));
  }

  const std::string& file_;
  GraspFileContents& out_;
  std::map<std::string, Preshape> preshapes_;
};

}  // namespace

namespace detail {
void experimentsFromElement(const XmlElement& root, const std::string& file,
                            GraspFileContents& out) {
  for (const auto& c : root.children) {
    if (localName(c.name) == "experiment") {
      ExperimentReader(file, out).read(c);
    } else {
      out.warnings.push_back(errorAt(file, c.location.line, c.location.column,
                                     c.describe() + ": ignored (expected <experiment>)"));
      out.warnings.back().severity = rw::common::Diagnostic::Severity::kWarning;
    }
  }
}
}  // namespace detail

GraspFileContents parseExperimentXml(std::string_view text, const std::filesystem::path& file) {
  const auto top = detail::parseXmlOrThrow(text, file);
  if (top.size() != 1 || detail::localName(top.front().name) != "visgrab") {
    throw rw::common::LoadError(
        {detail::errorAt(file.string(), top.empty() ? 0 : top.front().location.line,
                         top.empty() ? 0 : top.front().location.column,
                         "expected one root element <visgrab> (VisGraB experiment file)")});
  }
  GraspFileContents out;
  detail::experimentsFromElement(top.front(), file.string(), out);
  return out;
}

GraspFileContents readExperimentXml(const std::filesystem::path& file) {
  return parseExperimentXml(detail::readFileOrThrow(file, "the experiment file"), file);
}

}  // namespace visgrab::taskio
