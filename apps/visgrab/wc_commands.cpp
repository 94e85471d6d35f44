#include "wc_commands.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

#include "rw/loaders/workcell_loader.hpp"
#include "rw/math/rpy.hpp"

namespace visgrab::app {

namespace {

using rw::kinematics::Frame;
using rw::kinematics::FrameId;
using rw::kinematics::FrameType;
using rw::models::WorkCell;

std::string fmt(double v, int precision = 6) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string typeName(const Frame& f) {
  switch (f.type()) {
    case FrameType::kFixed:
      return f.isEndEffector() ? "end-effector" : "fixed";
    case FrameType::kMovable:
      return "movable";
    case FrameType::kRevolute:
      return "revolute";
    case FrameType::kPrismatic:
      return "prismatic";
  }
  return "?";
}

std::string poseText(const rw::math::Transform3D& X) {
  const auto& p = X.translation();
  const rw::math::Vector3D rpy = rw::math::rotationToRpy(X.linear()) * rw::math::kRad2Deg;
  std::ostringstream os;
  os << "pos (" << fmt(p.x()) << " " << fmt(p.y()) << " " << fmt(p.z()) << ") m, rpy ("
     << fmt(rpy.x()) << " " << fmt(rpy.y()) << " " << fmt(rpy.z()) << ") deg";
  return os.str();
}

void printFrame(const WorkCell& wc, FrameId id, const std::string& indent, bool last, bool root) {
  const Frame& f = wc.frames().frame(id);
  std::cout << indent << (root ? "" : (last ? "`- " : "|- ")) << f.name() << "  [" << typeName(f)
            << (f.isDependent() ? ", dependent" : "") << (f.isPassive() ? ", passive" : "")
            << (f.isDaf() ? ", daf" : "") << "]";
  if (!root) std::cout << "  " << poseText(f.fixedTransform());
  std::cout << "\n";
  const auto& children = wc.frames().children(id);
  const std::string childIndent = root ? indent : indent + (last ? "   " : "|  ");
  for (std::size_t i = 0; i < children.size(); ++i) {
    printFrame(wc, children[i], childIndent, i + 1 == children.size(), false);
  }
}

std::string limitText(const Frame& f) {
  const double scale = f.type() == FrameType::kRevolute ? rw::math::kRad2Deg : 1.0;
  const char* unit = f.type() == FrameType::kRevolute ? "deg" : "m";
  const auto& l = f.limits();
  std::ostringstream os;
  os << "[" << fmt(l.lower * scale) << ", " << fmt(l.upper * scale) << "] " << unit << ", vel "
     << fmt(l.velocity * scale) << " " << unit << "/s, acc " << fmt(l.acceleration * scale) << " "
     << unit << "/s^2";
  return os.str();
}

void printDevices(const WorkCell& wc) {
  std::cout << "\nDevices (" << wc.devices().size() << "):\n";
  for (const auto& d : wc.devices()) {
    const auto& tree = wc.frames();
    std::cout << "  " << d->name() << " ("
              << (d->kind() == rw::models::Device::Kind::kTree ? "tree" : "serial")
              << "): " << d->dof() << " DOF, " << d->joints().size() << " joints, base "
              << tree.frame(d->base()).name() << "\n    ends:";
    for (const FrameId e : d->ends()) std::cout << " " << tree.frame(e).name();
    std::cout << "\n    joints (q index, name, type, limits):\n";
    int index = 0;
    for (const FrameId j : d->joints()) {
      const Frame& f = tree.frame(j);
      std::cout << "      " << (f.isActiveJoint() ? std::to_string(index++) : std::string("-"))
                << "  " << f.name() << "  " << typeName(f) << "  ";
      if (f.isDependent()) {
        const auto& dep = *f.dependency();
        std::cout << "q = " << fmt(dep.gain) << " * " << tree.frame(dep.owner).name() << " + "
                  << fmt(dep.offset) << "\n";
      } else {
        std::cout << (f.isPassive() ? "passive, " : "") << limitText(f) << "\n";
      }
    }
    for (const auto& [name, q] : d->configurations()) {
      std::cout << "    configuration " << name << ": (";
      for (Eigen::Index i = 0; i < q.size(); ++i) std::cout << (i ? " " : "") << fmt(q[i]);
      std::cout << ")\n";
    }
  }
}

std::string geometryText(const rw::models::GeometryInstance& g) {
  std::ostringstream os;
  os << g.name << ": " << rw::geometry::geometryTypeName(g.geometry->type());
  if (g.geometry->type() == rw::geometry::GeometryType::kMesh) {
    os << " " << g.geometry->sourceFile() << " (" << g.geometry->triangles().triangles.size()
       << " triangles" << (g.geometry->isConvex() ? ", convex" : "") << ")";
  } else {
    for (const double p : g.geometry->parameters()) os << " " << fmt(p);
  }
  return os.str();
}

void printGeometry(const WorkCell& wc) {
  std::cout << "\nGeometry (" << wc.objects().size() << " frames):\n";
  for (const auto& o : wc.objects()) {
    std::cout << "  " << wc.frames().frame(o.frame).name() << "\n";
    for (const auto& g : o.collision) std::cout << "    collision " << geometryText(g) << "\n";
    for (const auto& g : o.visual) std::cout << "    visual    " << geometryText(g) << "\n";
  }
  std::cout << "\nCollision setup: " << wc.collisionSetup().excludePairs.size()
            << " excluded frame pairs; proximity rules: " << wc.proximitySetup().rules.size()
            << (wc.proximitySetup().useExcludeStaticPairs ? " (static pairs excluded)" : "")
            << "\n";
}

void printWarnings(const std::vector<rw::common::Diagnostic>& warnings) {
  for (const auto& w : warnings) std::cerr << w.format() << "\n";
}

int runInfo(const std::vector<std::string>& args) {
  const Arguments a(args, {});
  a.rejectUnknown({});
  a.requirePositionals(1, "FILE (a .wc.xml workcell)");
  std::vector<rw::common::Diagnostic> warnings;
  std::unique_ptr<WorkCell> wc;
  try {
    wc = rw::loaders::loadWorkCell(a.positionals()[0], &warnings);
  } catch (const rw::common::LoadError& e) {
    printWarnings(warnings);
    std::cerr << e.what() << "\n";
    return 1;
  }
  printWarnings(warnings);
  std::cout << "WorkCell \"" << wc->name() << "\"  (" << wc->fileName() << ")\n\nFrames ("
            << wc->frames().size() << "):\n";
  printFrame(*wc, rw::kinematics::FrameTree::kWorld, "  ", true, true);
  printDevices(*wc);
  printGeometry(*wc);
  return 0;
}

int runCheck(const std::vector<std::string>& args) {
  const Arguments a(args, {});
  a.rejectUnknown({});
  a.requirePositionals(1, "FILE (a .wc.xml workcell)");
  const auto diagnostics = rw::loaders::checkWorkCell(a.positionals()[0]);
  std::size_t errors = 0;
  for (const auto& d : diagnostics) {
    std::cerr << d.format() << "\n";
    if (d.severity == rw::common::Diagnostic::Severity::kError) ++errors;
  }
  const std::size_t warnings = diagnostics.size() - errors;
  std::cout << a.positionals()[0] << ": " << errors << " error(s), " << warnings << " warning(s)\n";
  return errors == 0 ? 0 : 1;
}

}  // namespace

std::vector<Command> workcellCommands() {
  return {
      {"wc", "info", "FILE", "Print the frame tree, devices, joint order and limits, geometry.",
       runInfo},
      {"wc", "check", "FILE",
       "Validate a workcell; print every problem as file:line:col; exit 1 on errors.", runCheck},
  };
}

}  // namespace visgrab::app
