#include "wc_commands.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

#include "json_writer.hpp"
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

std::string kindName(rw::models::Device::Kind kind) {
  switch (kind) {
    case rw::models::Device::Kind::kSerial:
      return "serial";
    case rw::models::Device::Kind::kTree:
      return "tree";
    case rw::models::Device::Kind::kParallel:
      return "parallel";
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

std::string nameList(const WorkCell& wc, const std::vector<FrameId>& ids) {
  std::string text;
  for (const FrameId id : ids) text += (text.empty() ? "" : ", ") + wc.frames().frame(id).name();
  return text.empty() ? "(none)" : text;
}

// Full DOF, actuated and passive joints, and every junction's legs (chains, start -> end).
void printParallel(const WorkCell& wc, const rw::models::ParallelKinematics& p,
                   const std::string& indent) {
  const auto& tree = wc.frames();
  std::cout << indent << "full DOF " << p.fullDof() << " ("
            << p.fullDof() - static_cast<int>(p.passiveJoints().size()) << " active + "
            << p.passiveJoints().size() << " passive), " << p.allJoints().size() << " joints\n"
            << indent << "actuated joints (" << p.actuatedJoints().size()
            << "): " << nameList(wc, p.actuatedJoints()) << "\n"
            << indent << "passive joints (" << p.passiveJoints().size()
            << "): " << nameList(wc, p.passiveJoints()) << "\n"
            << indent << "junctions (" << p.junctions().size() << "):\n";
  for (std::size_t j = 0; j < p.junctions().size(); ++j) {
    const auto& legs = p.junctions()[j].legs;
    std::cout << indent << "  " << j + 1 << ": " << legs.size() << " legs\n";
    for (const auto& leg : legs) {
      std::string chains;
      for (const std::string& c : leg.chains) chains += (chains.empty() ? "" : " ") + c;
      std::cout << indent << "     leg \"" << chains << "\": " << tree.frame(leg.start).name()
                << " -> " << tree.frame(leg.end).name() << "\n";
    }
  }
}

void printDevices(const WorkCell& wc) {
  std::cout << "\nDevices (" << wc.devices().size() << "):\n";
  for (const auto& d : wc.devices()) {
    const auto& tree = wc.frames();
    std::cout << "  " << d->name() << " (" << kindName(d->kind()) << "): " << d->dof() << " DOF, "
              << d->joints().size() << " joints, base " << tree.frame(d->base()).name()
              << "\n    ends:";
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
    if (d->parallel() != nullptr) printParallel(wc, *d->parallel(), "    ");
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

// --- wc info --json (docs/schemas/wc-info.schema.json) -------------------------------------

void writeFramesJson(JsonWriter& j, const WorkCell& wc) {
  j.key("frames").beginArray();
  for (const Frame& f : wc.frames().frames()) {
    j.beginObject().key("name").value(f.name()).key("parent");
    if (f.parent().valid()) {
      j.value(wc.frames().frame(f.parent()).name());
    } else {
      j.null();
    }
    const auto& X = f.fixedTransform();
    const rw::math::Vector3D rpy = rw::math::rotationToRpy(X.linear());
    j.key("type").value(typeName(f)).key("dependent").value(f.isDependent());
    j.key("passive").value(f.isPassive()).key("daf").value(f.isDaf());
    j.key("position").numbers({X.translation().x(), X.translation().y(), X.translation().z()});
    j.key("rpy").numbers({rpy.x(), rpy.y(), rpy.z()}).endObject();
  }
  j.endArray();
}

void writeNamesJson(JsonWriter& j, const WorkCell& wc, const std::vector<FrameId>& ids) {
  j.beginArray();
  for (const FrameId id : ids) j.value(wc.frames().frame(id).name());
  j.endArray();
}

void writeParallelJson(JsonWriter& j, const WorkCell& wc, const rw::models::ParallelKinematics& p) {
  j.key("parallel").beginObject().key("full_dof").value(p.fullDof());
  j.key("actuated_joints");
  writeNamesJson(j, wc, p.actuatedJoints());
  j.key("passive_joints");
  writeNamesJson(j, wc, p.passiveJoints());
  j.key("junctions").beginArray();
  for (const auto& junction : p.junctions()) {
    j.beginObject().key("legs").beginArray();
    for (const auto& leg : junction.legs) {
      j.beginObject().key("chains").beginArray();
      for (const std::string& c : leg.chains) j.value(c);
      j.endArray().key("start").value(wc.frames().frame(leg.start).name());
      j.key("end").value(wc.frames().frame(leg.end).name()).endObject();
    }
    j.endArray().endObject();
  }
  j.endArray().endObject();
}

void writeDevicesJson(JsonWriter& j, const WorkCell& wc) {
  const auto& tree = wc.frames();
  j.key("devices").beginArray();
  for (const auto& d : wc.devices()) {
    j.beginObject().key("name").value(d->name());
    j.key("kind").value(kindName(d->kind()));
    j.key("dof").value(d->dof()).key("base").value(tree.frame(d->base()).name());
    j.key("ends").beginArray();
    for (const FrameId e : d->ends()) j.value(tree.frame(e).name());
    j.endArray().key("joints").beginArray();
    int index = 0;
    for (const FrameId id : d->joints()) {
      const Frame& f = tree.frame(id);
      j.beginObject().key("name").value(f.name()).key("type").value(typeName(f));
      j.key("q_index");
      if (f.isActiveJoint()) {
        j.value(index++);
      } else {
        j.null();
      }
      j.key("passive").value(f.isPassive()).key("dependency");
      if (f.isDependent()) {
        const auto& dep = *f.dependency();
        j.beginObject().key("owner").value(tree.frame(dep.owner).name());
        j.key("gain").value(dep.gain).key("offset").value(dep.offset).endObject();
      } else {
        j.null();
      }
      const auto& l = f.limits();
      j.key("limits").beginObject().key("lower").value(l.lower).key("upper").value(l.upper);
      j.key("velocity").value(l.velocity).key("acceleration").value(l.acceleration);
      j.endObject().endObject();
    }
    j.endArray().key("configurations").beginArray();
    for (const auto& [name, q] : d->configurations()) {
      j.beginObject().key("name").value(name).key("q");
      j.numbers(std::vector<double>(q.data(), q.data() + q.size())).endObject();
    }
    j.endArray();
    if (d->parallel() != nullptr) writeParallelJson(j, wc, *d->parallel());
    j.endObject();
  }
  j.endArray();
}

void writeGeometryJson(JsonWriter& j, const rw::models::GeometryInstance& g) {
  const auto& geometry = *g.geometry;
  const bool mesh = geometry.type() == rw::geometry::GeometryType::kMesh;
  j.beginObject().key("name").value(g.name);
  j.key("type").value(rw::geometry::geometryTypeName(geometry.type()));
  j.key("file");
  if (mesh) {
    j.value(geometry.sourceFile());
  } else {
    j.null();
  }
  j.key("triangles");
  if (mesh) {
    j.value(geometry.triangles().triangles.size());
  } else {
    j.null();
  }
  j.key("convex").value(geometry.isConvex());
  const auto& p = geometry.parameters();
  j.key("parameters").numbers(std::vector<double>(p.begin(), p.end())).endObject();
}

void printInfoJson(const WorkCell& wc) {
  JsonWriter j(std::cout);
  j.beginObject().key("schema").value("visgrab/wc-info/1");
  j.key("name").value(wc.name()).key("file").value(wc.fileName());
  writeFramesJson(j, wc);
  writeDevicesJson(j, wc);
  j.key("objects").beginArray();
  for (const auto& o : wc.objects()) {
    j.beginObject().key("frame").value(wc.frames().frame(o.frame).name());
    j.key("collision").beginArray();
    for (const auto& g : o.collision) writeGeometryJson(j, g);
    j.endArray().key("visual").beginArray();
    for (const auto& g : o.visual) writeGeometryJson(j, g);
    j.endArray().endObject();
  }
  j.endArray();
  j.key("collision_excluded_pairs").value(wc.collisionSetup().excludePairs.size());
  j.key("proximity_rules").value(wc.proximitySetup().rules.size());
  j.endObject().finish();
}

int runInfo(const Arguments& a) {
  const std::string file = a.positionals().at(0);
  std::vector<rw::common::Diagnostic> warnings;
  std::unique_ptr<WorkCell> wc;
  try {
    wc = rw::loaders::loadWorkCell(file, &warnings);
  } catch (const rw::common::LoadError& e) {
    printWarnings(warnings);
    std::cerr << e.what() << "\n";
    return 1;
  }
  printWarnings(warnings);
  if (a.flag("json")) {
    printInfoJson(*wc);
    return 0;
  }
  std::cout << "WorkCell \"" << wc->name() << "\"  (" << wc->fileName() << ")\n\nFrames ("
            << wc->frames().size() << "):\n";
  printFrame(*wc, rw::kinematics::FrameTree::kWorld, "  ", true, true);
  printDevices(*wc);
  printGeometry(*wc);
  return 0;
}

// After a clean check: the closed loops of each parallel device, so that a hand designer sees
// how the junctions were read.
void printParallelSummaries(const std::string& file) {
  std::unique_ptr<WorkCell> wc;
  try {
    wc = rw::loaders::loadWorkCell(file);
  } catch (const rw::common::LoadError&) {
    return;
  }
  for (const auto& d : wc->devices()) {
    if (d->parallel() == nullptr) continue;
    std::cout << "parallel device " << d->name() << ": " << d->dof() << " DOF\n";
    printParallel(*wc, *d->parallel(), "  ");
  }
}

int runCheck(const Arguments& a) {
  const std::string file = a.positionals().at(0);
  const auto diagnostics = rw::loaders::checkWorkCell(file);
  std::size_t errors = 0;
  for (const auto& d : diagnostics) {
    std::cerr << d.format() << "\n";
    if (d.severity == rw::common::Diagnostic::Severity::kError) ++errors;
  }
  const std::size_t warnings = diagnostics.size() - errors;
  std::cout << file << ": " << errors << " error(s), " << warnings << " warning(s)\n";
  if (errors == 0) printParallelSummaries(file);
  return errors == 0 ? 0 : 1;
}

}  // namespace

void addWorkcellCommands(CommandLine& cli) {
  CLI::App& wc = cli.addGroup("wc", "Workcell files (.wc.xml): print one, check one.");
  CLI::App& info = cli.addCommand(
      &wc, "info",
      "Print the frame tree (poses in m and RobWork RPY degrees), devices, joint order and "
      "limits (rad or m), geometry.",
      guarded(runInfo));
  info.add_option("FILE", "The workcell (.wc.xml)")->required()->type_name("");
  addFlag(info, "--json",
          "Print JSON instead (docs/schemas/wc-info.schema.json; SI units: m, rad)");
  CLI::App& check = cli.addCommand(
      &wc, "check", "Validate a workcell; print every problem as file:line:col; exit 1 on errors.",
      guarded(runCheck));
  check.add_option("FILE", "The workcell (.wc.xml)")->required()->type_name("");
}

}  // namespace visgrab::app
