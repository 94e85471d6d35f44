#include "visgrab/grasp/hand_grasp_setup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <utility>

#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"

namespace visgrab::grasp {

namespace {

using rw::common::DiagnosticSink;
using rw::kinematics::FrameId;
using rw::math::Q;

std::string inQuotes(std::string_view s) { return "\"" + std::string(s) + "\""; }

// A number as a message shows it ("0.08", "-0.01", "1e-07").
std::string shortNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

Q toQ(const std::vector<double>& v) {
  return Eigen::Map<const Q>(v.data(), static_cast<Eigen::Index>(v.size()));
}

double tauFunction(TauFunction f, double angle) {
  switch (f) {
    case TauFunction::kOne:
      return 1.0;
    case TauFunction::kCos:
      return std::cos(angle);
    case TauFunction::kSecant:
      return 1.0 / std::cos(angle);
  }
  return 1.0;
}

}  // namespace

Q TauRule::evaluate(const Q& qOpen) const {
  Q tau = base;
  for (const TauAdjust& a : adjust) {
    const double angle = qOpen[a.angleIndex];
    if (!(angle >= a.atLeast && angle < a.below)) continue;
    const double value =
        std::max(a.floor, a.gain * base[a.source] * tauFunction(a.function, angle));
    for (const int j : a.joints) tau[j] = value;
  }
  return tau;
}

/// Second pass of the loader: checks names and lengths against the hand's model.
class SetupBuilder {
 public:
  SetupBuilder(HandGraspSetup& setup, DiagnosticSink& sink) : s_(setup), sink_(sink) {}

  bool build() {
    const GraspDescription& d = s_.description_;
    s_.device_ = s_.workcell_->findDevice(d.device);
    if (s_.device_ == nullptr) {
      error(d.where,
            "unknown device " + inQuotes(d.device) + " in workcell " + inQuotes(d.workcell));
      return false;
    }
    s_.defaultState_ = s_.workcell_->defaultState();
    if (!resolvePlacement(d.where)) return false;
    if (!resolveTcp(d.tcp, d.where, s_.tcp_)) return false;
    s_.tcpName_ = s_.workcell_->frames().frame(s_.tcp_).name();
    s_.X_base_tcp_ = relative(s_.placement_, s_.tcp_);
    buildTauRule(d.tauRule);
    s_.hasClosingRule_ = d.closing.has_value();
    s_.closeOffset_ = closing(d.closing.value_or(std::vector<CloseOffsetSpec>{}));
    for (const PreShapeSpec& p : d.preshapes) buildPreshape(p);
    if (d.contactIk) buildContactIk(*d.contactIk);
    if (d.jawFrame) buildJawFrame(*d.jawFrame);
    return !sink_.hasErrors();
  }

 private:
  void error(const SourceLocation& where, std::string message) {
    sink_.error(where, std::move(message));
  }

  rw::math::Transform3D relative(FrameId from, FrameId to) const {
    return rw::kinematics::relativeTransform(s_.workcell_->frames(), s_.defaultState_, from, to);
  }

  FrameId findFrame(const std::string& name) const {
    const FrameId scoped = s_.workcell_->findFrame(s_.device_->name() + "." + name);
    return scoped.valid() ? scoped : s_.workcell_->findFrame(name);
  }

  // The device's base if it is Movable, else the Movable frame holding the base rigidly.
  bool resolvePlacement(const SourceLocation& where) {
    const auto& tree = s_.workcell_->frames();
    const auto& base = tree.frame(s_.device_->base());
    FrameId f = s_.device_->base();
    while (f.valid() && tree.frame(f).type() == rw::kinematics::FrameType::kFixed) {
      f = tree.frame(f).parent();
    }
    if (!f.valid() || tree.frame(f).type() != rw::kinematics::FrameType::kMovable) {
      error(where, "the base frame " + inQuotes(base.name()) + " of device " +
                       inQuotes(s_.device_->name()) +
                       " must be Movable, or be held rigidly by a Movable frame (the grasp "
                       "utilities place the hand by it; a device file that cannot be edited "
                       "goes after a frame such as <Frame name=\"Mount\" type=\"Movable\"/>)");
      return false;
    }
    s_.placement_ = f;
    return true;
  }

  // A frame of the device, or after it, rigidly attached to the placement frame (no joint or
  // movable frame between).
  bool resolveTcp(const std::string& name, const SourceLocation& where, FrameId& out) {
    out = findFrame(name);
    const auto& tree = s_.workcell_->frames();
    FrameId f = out;
    while (f.valid() && f != s_.placement_ &&
           tree.frame(f).type() == rw::kinematics::FrameType::kFixed) {
      f = tree.frame(f).parent();
    }
    if (!out.valid() || (!s_.device_->contains(out) && f != s_.placement_)) {
      error(where, "unknown TCP frame " + inQuotes(name) + " (no such frame in device " +
                       inQuotes(s_.device_->name()) + " or rigidly attached to it)");
      return false;
    }
    if (f != s_.placement_) {
      error(where, "TCP frame " + inQuotes(name) + " must be rigidly attached to the base, but " +
                       inQuotes(tree.frame(f).name()) + " moves");
      return false;
    }
    return true;
  }

  std::string jointList() const {
    std::string list;
    for (const FrameId j : s_.device_->activeJoints()) {
      const std::string& full = s_.workcell_->frames().frame(j).name();
      const std::string prefix = s_.device_->name() + ".";
      list += (list.empty() ? "" : ", ") +
              (full.rfind(prefix, 0) == 0 ? full.substr(prefix.size()) : full);
    }
    return list;
  }

  // DOF index of an active joint, or -1 (reported).
  int joint(const std::string& name, const SourceLocation& where) {
    const FrameId f = findFrame(name);
    const auto& active = s_.device_->activeJoints();
    const auto it = std::find(active.begin(), active.end(), f);
    if (it != active.end()) return static_cast<int>(it - active.begin());
    const bool dependent = f.valid() && s_.workcell_->frames().frame(f).isDependent();
    error(where, (dependent ? "joint " + inQuotes(name) + " is dependent, not a DOF"
                            : "unknown joint " + inQuotes(name)) +
                     "; the joints of " + inQuotes(s_.device_->name()) + " are " + jointList());
    return -1;
  }

  bool length(const std::vector<double>& v, std::string_view what, const SourceLocation& where) {
    if (static_cast<int>(v.size()) == s_.dof()) return true;
    error(where, std::string(what) + " has " + std::to_string(v.size()) + " values, expected " +
                     std::to_string(s_.dof()) + " (one per DOF of " + inQuotes(s_.device_->name()) +
                     ": " + jointList() + ")");
    return false;
  }

  Q closing(const std::vector<CloseOffsetSpec>& offsets) {
    Q out = Q::Zero(s_.dof());
    for (const CloseOffsetSpec& o : offsets) {
      const int j = joint(o.joint, o.where);
      if (j < 0) continue;
      const auto& frame = s_.workcell_->frames().frame(s_.device_->activeJoints()[j]);
      const bool revolute = frame.type() == rw::kinematics::FrameType::kRevolute;
      out[j] = revolute ? o.value * rw::math::kDeg2Rad : o.value;
    }
    return out;
  }

  void buildTauRule(const TauRuleSpec& spec) {
    // One value stands for every DOF.
    const std::vector<double> base =
        spec.base.size() == 1
            ? std::vector<double>(static_cast<std::size_t>(s_.dof()), spec.base.front())
            : spec.base;
    if (!length(base, "<TauMax> base", spec.where)) return;
    s_.tauRule_.base = toQ(base);
    for (const TauAdjustSpec& a : spec.adjust) {
      TauAdjust r;
      r.angleIndex = joint(a.angleJoint, a.where);
      r.source = joint(a.source, a.where);
      if (a.atLeastDeg) r.atLeast = *a.atLeastDeg * rw::math::kDeg2Rad;
      if (a.belowDeg) r.below = *a.belowDeg * rw::math::kDeg2Rad;
      r.gain = a.gain;
      r.function = a.function;
      r.floor = a.floor;
      bool ok = r.angleIndex >= 0 && r.source >= 0;
      for (const std::string& name : a.joints) {
        r.joints.push_back(joint(name, a.where));
        ok = ok && r.joints.back() >= 0;
      }
      if (ok) s_.tauRule_.adjust.push_back(std::move(r));
    }
  }

  void buildPreshape(const PreShapeSpec& p) {
    const std::string what = "<PreShape name=\"" + p.name + "\"> ";
    bool ok = length(p.qOpen, what + "qOpen", p.where);
    ok = length(p.qClosed, what + "qClosed", p.where) && ok;
    if (p.tauMax) ok = length(*p.tauMax, what + "tauMax", p.where) && ok;
    std::vector<std::string> all{p.name};
    all.insert(all.end(), p.aliases.begin(), p.aliases.end());
    for (const std::string& n : all) {
      const auto [it, inserted] = names_.emplace(n, p.where.line);
      if (!inserted) {
        error(p.where, "pre-shape name " + inQuotes(n) + " is already used (line " +
                           std::to_string(it->second) + ")");
        ok = false;
      }
    }
    PreShape shape;
    shape.name = p.name;
    shape.aliases = p.aliases;
    shape.qOpen = toQ(p.qOpen);
    shape.qClosed = toQ(p.qClosed);
    if (!p.tcp.empty()) {
      FrameId frame;
      if (!resolveTcp(p.tcp, p.where, frame)) return;
      shape.X_shapeTcp_tcp = relative(frame, s_.tcp_);
    }
    if (!ok || s_.tauRule_.base.size() != s_.dof()) return;
    shape.tauMax = p.tauMax ? toQ(*p.tauMax) : s_.tauRule_.evaluate(shape.qOpen);
    s_.preshapes_.push_back(std::move(shape));
  }

  int fingertip(const std::vector<Fingertip>& tips, const std::string& name,
                const SourceLocation& where) {
    for (std::size_t i = 0; i < tips.size(); ++i) {
      if (tips[i].name == name) return static_cast<int>(i);
    }
    error(where, "unknown fingertip " + inQuotes(name));
    return -1;
  }

  void buildIkGrasp(const IkGraspSpec& g, ContactIkSettings& ik) {
    IkGrasp out;
    out.contacts = g.contacts;
    bool ok = true;
    if (static_cast<int>(g.fingers.size()) != g.contacts) {
      error(g.where, "<Grasp contacts=\"" + std::to_string(g.contacts) + "\"> names " +
                         std::to_string(g.fingers.size()) + " fingers; expected one per contact");
      ok = false;
    }
    for (const std::string& f : g.fingers) {
      out.fingers.push_back(fingertip(ik.fingertips, f, g.where));
      ok = ok && out.fingers.back() >= 0;
    }
    for (const std::string& j : g.joints) {
      out.joints.push_back(joint(j, g.where));
      ok = ok && out.joints.back() >= 0;
    }
    if (g.joints.empty()) {
      for (int j = 0; j < s_.dof(); ++j) out.joints.push_back(j);
    }
    std::sort(out.joints.begin(), out.joints.end());
    out.joints.erase(std::unique(out.joints.begin(), out.joints.end()), out.joints.end());
    for (const auto& seed : g.seeds) {
      ok = length(seed, "<Seed> q", g.where) && ok;
      out.seeds.push_back(toQ(seed));
    }
    if (!g.closing && !s_.hasClosingRule_) {
      error(g.where,
            "this contact grasp has no closing rule: give it a <Closing> or give the "
            "description one (after the <PreShape>s)");
      ok = false;
    }
    out.closeOffset = g.closing ? closing(*g.closing) : s_.closeOffset_;
    if (ok) ik.grasps.push_back(std::move(out));
  }

  void buildContactIk(const ContactIkSpec& spec) {
    ContactIkSettings ik;
    ik.backoff = spec.backoff;
    ik.maxPositionError = spec.maxPositionError;
    ik.maxDirectionError = spec.maxDirectionErrorDeg * rw::math::kDeg2Rad;
    ik.maxApproachError = spec.maxApproachErrorDeg * rw::math::kDeg2Rad;
    ik.directionWeight = spec.directionWeight;
    ik.approachWeight = spec.approachWeight;
    if (!(spec.maxPositionError > 0.0) || spec.backoff < 0.0) {
      error(spec.where, "<ContactIK> needs maxPositionError > 0 and backoff >= 0");
    }
    if (spec.approachAxis.norm() < 1e-9) error(spec.where, "approachAxis must not be zero");
    ik.approachAxisInBase = (s_.X_base_tcp_.linear() * spec.approachAxis).normalized();
    for (const FingertipSpec& f : spec.fingertips) {
      const FrameId frame = findFrame(f.frame);
      if (!frame.valid() || !s_.device_->contains(frame)) {
        error(f.where, "unknown fingertip frame " + inQuotes(f.frame) +
                           " (no such frame in device " + inQuotes(s_.device_->name()) + ")");
      }
      if (f.normal.norm() < 1e-9) error(f.where, "the fingertip's normal must not be zero");
      const bool duplicate =
          std::any_of(ik.fingertips.begin(), ik.fingertips.end(),
                      [&](const Fingertip& other) { return other.name == f.name; });
      if (duplicate) error(f.where, "duplicate fingertip name " + inQuotes(f.name));
      ik.fingertips.push_back({f.name, frame, f.point, f.normal.normalized()});
    }
    for (const IkGraspSpec& g : spec.grasps) buildIkGrasp(g, ik);
    s_.contactIk_ = std::move(ik);
  }

  // The jaw frame's rotation in the frame it is written in: x = closing, z = approach, y = z x x.
  // Both axes are normalised first; they must be at right angles within kJawAxisTolerance (the
  // cosine of the angle between them): axes written to six digits pass, a wrong axis does not.
  bool jawRotation(const JawFrameSpec& spec, rw::math::Rotation3D& out) {
    constexpr double kJawAxisTolerance = 1e-6;
    bool ok = true;
    if (!(spec.approach.norm() > 1e-9)) {
      error(spec.where, "<JawFrame> approach must not be zero");
      ok = false;
    }
    if (!(spec.closing.norm() > 1e-9)) {
      error(spec.where, "<JawFrame> closing must not be zero");
      ok = false;
    }
    if (!ok) return false;
    const rw::math::Vector3D z = spec.approach.normalized();
    const rw::math::Vector3D x = spec.closing.normalized();
    const double cosine = x.dot(z);
    if (std::abs(cosine) > kJawAxisTolerance) {
      error(spec.where,
            "<JawFrame> approach and closing must be at right angles, but they are " +
                shortNumber(std::acos(std::clamp(cosine, -1.0, 1.0)) * rw::math::kRad2Deg) +
                " deg apart (the cosine of the angle is " + shortNumber(cosine) +
                "; at most 1e-06 is accepted)");
      return false;
    }
    out.col(0) = x;
    out.col(1) = z.cross(x);
    out.col(2) = z;
    return true;
  }

  void buildJawFrame(const JawFrameSpec& spec) {
    bool ok = true;
    if (!(spec.stroke > 0.0)) {
      error(spec.where,
            "<JawFrame> stroke must be greater than 0 (the opening between the pads "
            "at the pre-shape, m), not " +
                shortNumber(spec.stroke));
      ok = false;
    }
    if (!(spec.tipDepth >= 0.0)) {
      error(spec.where,
            "<JawFrame> tipDepth must be at least 0 (the fingertips' front lies beyond the pad "
            "centre along the approach), not " +
                shortNumber(spec.tipDepth));
      ok = false;
    }
    rw::math::Rotation3D R = rw::math::Rotation3D::Identity();
    ok = jawRotation(spec, R) && ok;
    std::size_t index = s_.preshapes_.size();
    for (std::size_t i = 0; i < s_.preshapes_.size(); ++i) {
      const PreShape& p = s_.preshapes_[i];
      if (p.name == spec.preshape ||
          std::find(p.aliases.begin(), p.aliases.end(), spec.preshape) != p.aliases.end()) {
        index = i;
        break;
      }
    }
    if (index == s_.preshapes_.size()) {
      std::string known;
      for (const PreShape& p : s_.preshapes_) known += (known.empty() ? "" : ", ") + p.name;
      error(spec.where, "<JawFrame> names unknown pre-shape " + inQuotes(spec.preshape) +
                            " (the description's pre-shapes: " + (known.empty() ? "none" : known) +
                            ")");
      ok = false;
    }
    const FrameId frame = spec.frame.empty() ? s_.tcp_ : findFrame(spec.frame);
    if (!frame.valid() || (!s_.device_->contains(frame) && !rigidOnPlacement(frame))) {
      error(spec.where, "<JawFrame> names unknown frame " + inQuotes(spec.frame) +
                            " (no such frame in device " + inQuotes(s_.device_->name()) +
                            " or rigidly attached to it)");
      ok = false;
    }
    if (!ok) return;
    rw::kinematics::State state = s_.defaultState_;
    try {
      s_.device_->setQ(s_.preshapes_[index].qOpen, state);
    } catch (const std::exception& e) {
      error(spec.where, "<JawFrame>: the pre-shape " + inQuotes(spec.preshape) +
                            "'s qOpen cannot be set: " + e.what());
      return;
    }
    const rw::math::Transform3D X_tcp_frame =
        rw::kinematics::relativeTransform(s_.workcell_->frames(), state, s_.tcp_, frame);
    JawFrame jaw;
    jaw.X_tcp_jaw = X_tcp_frame * rw::math::makeTransform(R, spec.position);
    jaw.stroke = spec.stroke;
    jaw.tipDepth = spec.tipDepth;
    jaw.preshape = index;
    s_.jawFrame_ = jaw;
  }

  // True if `frame` is held by the placement frame through fixed frames only.
  bool rigidOnPlacement(FrameId frame) const {
    const auto& tree = s_.workcell_->frames();
    while (frame.valid() && frame != s_.placement_ &&
           tree.frame(frame).type() == rw::kinematics::FrameType::kFixed) {
      frame = tree.frame(frame).parent();
    }
    return frame == s_.placement_;
  }

  HandGraspSetup& s_;
  DiagnosticSink& sink_;
  std::map<std::string, int> names_;
};

std::unique_ptr<HandGraspSetup> HandGraspSetup::build(
    GraspDescription description, std::shared_ptr<const rw::models::WorkCell> workcell,
    DiagnosticSink& sink) {
  std::unique_ptr<HandGraspSetup> setup(new HandGraspSetup());
  setup->description_ = std::move(description);
  setup->workcell_ = std::move(workcell);
  if (!SetupBuilder(*setup, sink).build()) return nullptr;
  return setup;
}

const PreShape* HandGraspSetup::findPreshape(std::string_view name) const {
  for (const PreShape& p : preshapes_) {
    if (p.name == name) return &p;
    if (std::find(p.aliases.begin(), p.aliases.end(), name) != p.aliases.end()) return &p;
  }
  return nullptr;
}

namespace {

// The hand's workcell file loaded the way a scene includes it: as the only content of an empty
// workcell. So the file may be a device (the project's hands) or a fragment of several
// top-level elements (a Movable mount frame, a device file included from elsewhere, a TCP
// frame after it). Its messages say "included from" the description's workcell= line.
std::unique_ptr<rw::models::WorkCell> loadAsIncluded(const std::filesystem::path& wcFile,
                                                     const GraspDescription& description) {
  std::string xml(static_cast<std::size_t>(std::max(description.where.line - 1, 0)), '\n');
  xml += "<WorkCell name=\"\"><Include file=\"" +
         rw::common::escapeXml(std::filesystem::absolute(wcFile).lexically_normal().string()) +
         "\"/></WorkCell>\n";
  return rw::loaders::loadWorkCellFromString(xml, description.file);
}

}  // namespace

std::unique_ptr<HandGraspSetup> loadHandGraspSetupFromString(
    std::string_view xml, const std::filesystem::path& virtualFile) {
  DiagnosticSink sink;
  auto description = parseGraspDescription(xml, virtualFile, sink);
  if (!description) throw rw::common::LoadError(sink.take());
  const std::filesystem::path wcFile = virtualFile.parent_path() / description->workcell;
  std::shared_ptr<const rw::models::WorkCell> workcell;
  try {
    workcell = loadAsIncluded(wcFile, *description);
  } catch (const rw::common::LoadError& e) {
    std::vector<rw::common::Diagnostic> all = e.diagnostics();
    rw::common::Diagnostic note;
    note.file = description->file;
    note.line = description->where.line;
    note.column = description->where.column;
    note.message = "the hand's workcell " + inQuotes(wcFile.string()) + " failed to load";
    all.insert(all.begin(), note);
    throw rw::common::LoadError(std::move(all));
  }
  std::filesystem::path dynamics =
      description->dynamics.empty()
          ? wcFile.parent_path() /
                (wcFile.filename().string().substr(0, wcFile.filename().string().find('.')) +
                 "_dynamics.dwc.xml")
          : virtualFile.parent_path() / description->dynamics;
  auto setup = HandGraspSetup::build(std::move(*description), std::move(workcell), sink);
  if (!setup) throw rw::common::LoadError(sink.take());
  setup->workcellFile_ = std::filesystem::absolute(wcFile).lexically_normal();
  setup->dynamicsFile_ = std::filesystem::absolute(dynamics).lexically_normal();
  return setup;
}

std::filesystem::path graspDescriptionFile(const std::filesystem::path& fileOrFolder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(fileOrFolder, ec)) return fileOrFolder;
  std::vector<std::filesystem::path> found;
  for (const auto& e : std::filesystem::directory_iterator(fileOrFolder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() > 10 && name.ends_with(".grasp.xml") && e.is_regular_file(ec)) {
      found.push_back(e.path());
    }
  }
  std::sort(found.begin(), found.end());
  if (found.size() == 1) return found.front();
  rw::common::Diagnostic d;
  d.file = fileOrFolder.string();
  if (found.empty()) {
    d.message = "the hand folder " + fileOrFolder.string() +
                " holds no grasp description (*.grasp.xml; docs/adding-a-hand.md)";
  } else {
    d.message = "the hand folder " + fileOrFolder.string() + " holds " +
                std::to_string(found.size()) + " grasp descriptions (";
    for (std::size_t i = 0; i < found.size(); ++i) {
      d.message += (i ? ", " : "") + found[i].filename().string();
    }
    d.message += "); give the one to use";
  }
  throw rw::common::LoadError({d});
}

std::unique_ptr<HandGraspSetup> loadHandGraspSetup(const std::filesystem::path& fileOrFolder) {
  const std::filesystem::path file = graspDescriptionFile(fileOrFolder);
  return loadHandGraspSetupFromString(rw::common::readTextFileOrThrow(file), file);
}

}  // namespace visgrab::grasp
