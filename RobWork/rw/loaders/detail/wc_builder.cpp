#include "rw/loaders/detail/wc_builder.hpp"

#include <algorithm>
#include <functional>
#include <queue>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "rw/common/strings.hpp"
#include "rw/loaders/detail/setup_files.hpp"
#include "rw/loaders/detail/wc_geometry.hpp"
#include "rw/loaders/detail/wc_parallel.hpp"

namespace rw::loaders::detail {

using rw::kinematics::FrameId;
using rw::kinematics::FrameSpec;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;
using rw::models::Device;
using rw::models::WorkCell;

namespace {

constexpr int kWorldIndex = -1;
constexpr int kUnresolved = -2;

std::string_view lastComponent(std::string_view name) {
  const auto dot = name.rfind('.');
  return dot == std::string_view::npos ? name : name.substr(dot + 1);
}

bool isJointType(FrameType type) {
  return type == FrameType::kRevolute || type == FrameType::kPrismatic;
}

std::string where(const common::SourceLocation& location) {
  std::string text = location.file ? location.file->displayPath : std::string("?");
  return text + ":" + std::to_string(location.line);
}

// Resolves names, orders frames and creates the model.
class Builder {
 public:
  Builder(const WorkCellDesc& desc, common::DiagnosticSink& sink)
      : d_(desc),
        sink_(sink),
        parent_(desc.frames.size(), kUnresolved),
        owner_(desc.frames.size(), kWorldIndex),
        deviceLimits_(desc.frames.size()),
        ids_(desc.frames.size()),
        dropped_(desc.frames.size(), 0) {}

  std::unique_ptr<WorkCell> run(common::XmlReader& setupReader, const std::string& fileName);

 private:
  void indexNames();
  int lookup(const std::string& name) const;
  void unknown(const Origin& origin, const std::string& what, const std::string& name);
  void resolveParents();
  void resolveDependencies();
  void resolveDeviceLimits();
  void resolveModels();
  std::vector<int> order();
  void reportCycles(const std::vector<char>& placed);
  rw::kinematics::JointLimits limitsOf(int i) const;
  bool createFrames(WorkCell& wc, const std::vector<int>& order);
  void createDevices(WorkCell& wc);
  void checkConfigurations(const DeviceDesc& dd, const Device& device, Device::Spec& spec);
  void setDefaultState(WorkCell& wc);

  const WorkCellDesc& d_;
  common::DiagnosticSink& sink_;
  std::unordered_map<std::string, int> byName_;
  std::vector<std::string> names_;
  std::vector<int> parent_;
  std::vector<int> owner_;
  std::vector<std::vector<const LimitDesc*>> deviceLimits_;
  std::vector<FrameId> ids_;
  std::vector<char> dropped_;
  int suggestionsLeft_ = 20;
};

void Builder::indexNames() {
  for (std::size_t i = 0; i < d_.frames.size(); ++i) {
    const FrameDesc& f = d_.frames[i];
    if (f.name == FrameTree::kWorldName) {
      sink_.error(f.origin.location,
                  f.origin.element + ": the name " + f.name + " is reserved for the world frame");
      dropped_[i] = 1;
      continue;
    }
    const auto [it, fresh] = byName_.emplace(f.name, static_cast<int>(i));
    if (!fresh) {
      const Origin& first = d_.frames[static_cast<std::size_t>(it->second)].origin;
      sink_.error(f.origin.location, f.origin.element + ": duplicate frame name \"" + f.name +
                                         "\" (first declared at " + where(first.location) + ")");
      dropped_[i] = 1;
      continue;
    }
    names_.push_back(f.name);
  }
  names_.emplace_back(FrameTree::kWorldName);
}

int Builder::lookup(const std::string& name) const {
  if (name == FrameTree::kWorldName) return kWorldIndex;
  const auto it = byName_.find(name);
  return it == byName_.end() ? kUnresolved : it->second;
}

void Builder::unknown(const Origin& origin, const std::string& what, const std::string& name) {
  const std::string hint = suggestionsLeft_-- > 0 ? suggestName(name, names_) : std::string();
  sink_.error(origin.location, origin.element + ": unknown " + what + " \"" + name + "\"" + hint);
}

void Builder::resolveParents() {
  for (std::size_t i = 0; i < d_.frames.size(); ++i) {
    const FrameDesc& f = d_.frames[i];
    if (dropped_[i]) continue;
    parent_[i] = lookup(f.parent);
    if (parent_[i] == kUnresolved) unknown(f.origin, "refframe", f.parent);
  }
}

// Depend owners: looked up in the joint's scope, then in shorter enclosing scopes
// (reference §1.3); the owner must be an independent joint declared earlier.
void Builder::resolveDependencies() {
  for (std::size_t i = 0; i < d_.frames.size(); ++i) {
    const FrameDesc& f = d_.frames[i];
    if (!f.depend || dropped_[i]) continue;
    const DependDesc& dep = *f.depend;
    const std::string context = f.origin.element + ": <Depend on=\"" + dep.on + "\">";
    int found = kUnresolved;
    for (std::size_t k = dep.scope.size() + 1; k-- > 0 && found == kUnresolved;) {
      std::string name;
      for (std::size_t s = 0; s < k; ++s) name += dep.scope[s] + ".";
      found = lookup(name + dep.on);
    }
    if (found == kUnresolved || found == kWorldIndex) {
      std::string scope;
      for (const std::string& s : dep.scope) scope += s + ".";
      const std::string hint =
          suggestionsLeft_-- > 0 ? suggestName(scope + dep.on, names_) : std::string();
      sink_.error(dep.origin.location, context + ": no joint \"" + dep.on + "\" in scope \"" +
                                           scope + "\" or an enclosing one" + hint);
      continue;
    }
    const FrameDesc& o = d_.frames[static_cast<std::size_t>(found)];
    if (!isJointType(o.type)) {
      sink_.error(dep.origin.location, context + ": \"" + o.name + "\" is not a joint");
    } else if (o.depend) {
      sink_.error(dep.origin.location,
                  context + ": \"" + o.name + "\" depends on another joint itself");
    } else if (static_cast<std::size_t>(found) > i) {
      sink_.error(dep.origin.location, context + ": \"" + o.name +
                                           "\" must be declared before the joints that depend "
                                           "on it (it is at " +
                                           where(o.origin.location) + ")");
    } else {
      owner_[i] = found;
    }
  }
}

void Builder::resolveDeviceLimits() {
  for (const DeviceDesc& device : d_.devices) {
    for (const LimitDesc& limit : device.limits) {
      const int j = lookup(limit.joint);
      if (j == kUnresolved || j == kWorldIndex) {
        unknown(limit.origin, "refjoint", limit.joint);
      } else if (!isJointType(d_.frames[static_cast<std::size_t>(j)].type)) {
        sink_.error(limit.origin.location,
                    limit.origin.element + ": \"" + limit.joint + "\" is not a joint");
      } else {
        deviceLimits_[static_cast<std::size_t>(j)].push_back(&limit);
      }
    }
  }
}

void Builder::resolveModels() {
  for (const ModelDesc& m : d_.models) {
    if (lookup(m.frame) == kUnresolved) unknown(m.origin, "refframe", m.frame);
  }
}

// Parent-first order (Kahn's algorithm, document order among the ready frames). Dependent
// joints also wait for their owner.
std::vector<int> Builder::order() {
  const std::size_t n = d_.frames.size();
  std::vector<std::vector<int>> next(n);
  std::vector<int> waiting(n, 0);
  std::priority_queue<int, std::vector<int>, std::greater<>> ready;
  std::size_t live = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (dropped_[i]) continue;
    ++live;
    for (const int before : {parent_[i], owner_[i]}) {
      if (before >= 0) {
        next[static_cast<std::size_t>(before)].push_back(static_cast<int>(i));
        ++waiting[i];
      }
    }
    if (waiting[i] == 0) ready.push(static_cast<int>(i));
  }
  std::vector<int> sorted;
  std::vector<char> placed(n, 0);
  while (!ready.empty()) {
    const int i = ready.top();
    ready.pop();
    sorted.push_back(i);
    placed[static_cast<std::size_t>(i)] = 1;
    for (const int c : next[static_cast<std::size_t>(i)]) {
      if (--waiting[static_cast<std::size_t>(c)] == 0) ready.push(c);
    }
  }
  if (sorted.size() < live) {
    for (std::size_t i = 0; i < n; ++i) placed[i] = placed[i] || dropped_[i];
    reportCycles(placed);
  }
  return sorted;
}

// Reports each cycle of unplaced frames once, at its first frame in document order.
void Builder::reportCycles(const std::vector<char>& placed) {
  const std::size_t n = d_.frames.size();
  std::vector<char> visited(n, 0);
  bool reported = false;
  for (std::size_t start = 0; start < n; ++start) {
    if (placed[start] || visited[start]) continue;
    std::vector<int> path;
    std::unordered_map<int, std::size_t> position;
    int cur = static_cast<int>(start);
    while (cur >= 0 && !placed[static_cast<std::size_t>(cur)] &&
           !visited[static_cast<std::size_t>(cur)]) {
      visited[static_cast<std::size_t>(cur)] = 1;
      position[cur] = path.size();
      path.push_back(cur);
      cur = parent_[static_cast<std::size_t>(cur)];
    }
    const auto at = position.find(cur);
    if (cur < 0 || at == position.end()) continue;
    const std::vector<int> cycle(path.begin() + static_cast<std::ptrdiff_t>(at->second),
                                 path.end());
    const int first = *std::min_element(cycle.begin(), cycle.end());
    std::string chain;
    for (const int c : cycle) chain += d_.frames[static_cast<std::size_t>(c)].name + " -> ";
    chain += d_.frames[static_cast<std::size_t>(cycle.front())].name;
    const Origin& origin = d_.frames[static_cast<std::size_t>(first)].origin;
    sink_.error(origin.location,
                origin.element + ": frame cycle: " + chain + " (each is attached to the next)");
    reported = true;
  }
  if (!reported) {
    for (std::size_t i = 0; i < n; ++i) {
      if (placed[i]) continue;
      const Origin& origin = d_.frames[i].origin;
      sink_.error(origin.location, origin.element +
                                       ": the frame cannot be placed: it is attached below a "
                                       "joint that depends on a joint declared after it");
      break;
    }
  }
}

// Joint limits in SI units. Revolute limits are written in degrees; the device-level limits
// of a dependent joint are kept unconverted, as RobWork picks the factor with
// dynamic_cast<RevoluteJoint*>, which a DependentRevoluteJoint is not (reference §1.9).
// Limits written inside a dependent joint were already dropped by the parser (RobWork
// ignores them).
rw::kinematics::JointLimits Builder::limitsOf(int i) const {
  const FrameDesc& f = d_.frames[static_cast<std::size_t>(i)];
  rw::kinematics::JointLimits limits;
  if (!isJointType(f.type)) return limits;
  const double factor = (f.type == FrameType::kRevolute && !f.depend) ? rw::math::kDeg2Rad : 1.0;
  std::vector<const LimitDesc*> all;
  for (const LimitDesc& l : f.limits) all.push_back(&l);
  const auto& outside = deviceLimits_[static_cast<std::size_t>(i)];
  all.insert(all.end(), outside.begin(), outside.end());
  for (const LimitDesc* l : all) {
    switch (l->kind) {
      case LimitKind::kPosition:
        limits.lower = l->min * factor;
        limits.upper = l->max * factor;
        break;
      case LimitKind::kVelocity:
        limits.velocity = l->max * factor;
        break;
      case LimitKind::kAcceleration:
        limits.acceleration = l->max * factor;
        break;
    }
  }
  return limits;
}

bool Builder::createFrames(WorkCell& wc, const std::vector<int>& order) {
  for (const int i : order) {
    const FrameDesc& f = d_.frames[static_cast<std::size_t>(i)];
    FrameSpec spec;
    spec.name = f.name;
    const int p = parent_[static_cast<std::size_t>(i)];
    spec.parent = p == kWorldIndex ? FrameTree::kWorld : ids_[static_cast<std::size_t>(p)];
    spec.type = f.type;
    spec.transform = f.transform;
    spec.limits = limitsOf(i);
    if (f.depend) {
      spec.dependency = rw::kinematics::JointDependency{
          ids_[static_cast<std::size_t>(owner_[static_cast<std::size_t>(i)])], f.depend->gain,
          f.depend->offset};
    }
    spec.passive = f.passive;
    spec.endEffector = f.endEffector;
    spec.daf = f.daf;
    for (const PropertyDesc& prop : f.properties) spec.properties[prop.name] = prop.property;
    try {
      ids_[static_cast<std::size_t>(i)] = wc.frames().add(std::move(spec));
    } catch (const std::invalid_argument& e) {
      sink_.error(f.origin.location, f.origin.element + ": " + e.what());
      return false;
    }
  }
  return true;
}

// The named configurations that fit the device go into its spec; the others are errors.
void Builder::checkConfigurations(const DeviceDesc& dd, const Device& device, Device::Spec& spec) {
  const int dof = device.dof();
  for (const QDesc& q : dd.configurations) {
    if (static_cast<int>(q.values.size()) != dof) {
      sink_.error(q.origin.location, q.origin.element + ": " + std::to_string(q.values.size()) +
                                         " values, but device \"" + dd.name + "\" has " +
                                         std::to_string(dof) + (dof == 1 ? " degree" : " degrees") +
                                         " of freedom");
      continue;
    }
    spec.configurations[q.name] = Eigen::Map<const Eigen::VectorXd>(
        q.values.data(), static_cast<Eigen::Index>(q.values.size()));
  }
}

void Builder::createDevices(WorkCell& wc) {
  for (const DeviceDesc& dd : d_.devices) {
    Device::Spec spec;
    spec.name = dd.name;
    spec.kind = dd.tree ? Device::Kind::kTree : Device::Kind::kSerial;
    spec.base = ids_[static_cast<std::size_t>(dd.frames.front())];
    for (const PropertyDesc& p : dd.properties) spec.properties[p.name] = p.property;
    if (dd.parallel) {
      auto structure = buildParallelStructure(d_, dd, ids_, wc.frames(), sink_);
      if (!structure) continue;
      // RobWork: base and end of the first leg of the first junction.
      spec.kind = Device::Kind::kParallel;
      spec.base = structure->junctions.front().legs.front().start;
      spec.ends = {structure->junctions.front().legs.front().end};
      try {
        checkConfigurations(dd, Device(spec, wc.frames(), *structure), spec);
        wc.addDevice(std::move(spec), std::move(*structure));
      } catch (const std::invalid_argument& e) {
        sink_.error(dd.origin.location, dd.origin.element + ": " + e.what());
      }
      continue;
    }
    if (dd.tree) {
      for (const int i : dd.frames) {
        if (d_.frames[static_cast<std::size_t>(i)].endEffector) {
          spec.ends.push_back(ids_[static_cast<std::size_t>(i)]);
        }
      }
    }
    if (spec.ends.empty()) spec.ends.push_back(ids_[static_cast<std::size_t>(dd.frames.back())]);
    try {
      checkConfigurations(dd, Device(spec, wc.frames()), spec);
      wc.addDevice(std::move(spec));
    } catch (const std::invalid_argument& e) {
      sink_.error(dd.origin.location, dd.origin.element + ": " + e.what());
    }
  }
}

// Movable frames start at their given transform (FrameTree::makeState); a device's "Home"
// configuration sets its joints (a parallel device's junctions are closed from all joints at
// zero; a Home that cannot close them is an error at its <Q>).
void Builder::setDefaultState(WorkCell& wc) {
  rw::kinematics::State state = wc.frames().makeState();
  for (const DeviceDesc& dd : d_.devices) {
    const Device* device = wc.findDevice(dd.name);
    if (device == nullptr) continue;
    const auto home = device->configurations().find("Home");
    if (home == device->configurations().end()) continue;
    try {
      device->setQ(home->second, state);
    } catch (const rw::models::ClosureError& e) {
      for (const QDesc& q : dd.configurations) {
        if (q.name == "Home") sink_.error(q.origin.location, q.origin.element + ": " + e.what());
      }
    }
  }
  wc.setDefaultState(std::move(state));
}

std::unique_ptr<WorkCell> Builder::run(common::XmlReader& setupReader,
                                       const std::string& fileName) {
  indexNames();
  resolveParents();
  resolveDependencies();
  resolveDeviceLimits();
  resolveModels();
  if (sink_.hasErrors()) return nullptr;
  const std::vector<int> sorted = order();
  if (sink_.hasErrors()) return nullptr;
  auto wc = std::make_unique<WorkCell>(d_.name);
  if (!createFrames(*wc, sorted)) return nullptr;
  createDevices(*wc);
  if (sink_.hasErrors()) return nullptr;
  setDefaultState(*wc);
  if (sink_.hasErrors()) return nullptr;
  addGeometry(*wc, d_.models, sink_);
  buildSetups(*wc, d_, setupReader, sink_);
  for (const PropertyDesc& p : d_.properties) wc->properties()[p.name] = p.property;
  wc->setFileName(fileName);
  return wc;
}

}  // namespace

std::string suggestName(std::string_view wanted, const std::vector<std::string>& candidates) {
  constexpr std::size_t kLongest = 200;
  if (wanted.size() > kLongest) return {};
  const std::string_view wantedLast = lastComponent(wanted);
  const std::string* best = nullptr;
  std::size_t bestScore = std::string::npos;
  for (const std::string& c : candidates) {
    if (c.size() > kLongest || c == wanted) continue;
    std::size_t score = rw::common::editDistance(wanted, c);
    const bool sameLast = lastComponent(c) == wantedLast;
    if (sameLast) score = std::min<std::size_t>(score, 1);
    const std::size_t allowed = std::max<std::size_t>(2, wanted.size() / 4);
    if ((sameLast || score <= allowed) && score < bestScore) {
      best = &c;
      bestScore = score;
    }
  }
  return best == nullptr ? std::string() : "; did you mean \"" + *best + "\"?";
}

std::unique_ptr<WorkCell> buildWorkCell(const WorkCellDesc& desc, common::XmlReader& setupReader,
                                        const std::string& fileName, common::DiagnosticSink& sink) {
  return Builder(desc, sink).run(setupReader, fileName);
}

}  // namespace rw::loaders::detail
