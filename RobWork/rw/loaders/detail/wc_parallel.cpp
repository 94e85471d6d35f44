#include "rw/loaders/detail/wc_parallel.hpp"

#include <map>
#include <string>
#include <utility>

namespace rw::loaders::detail {

using rw::kinematics::FrameId;
using rw::models::Junction;
using rw::models::ParallelLeg;
using rw::models::ParallelStructure;

namespace {

// A serial chain of the device: indices into WorkCellDesc::frames, each frame hanging on the
// one before it; the first is the frame the chain starts from.
struct Chain {
  std::string name;
  std::vector<int> frames;
};

class ParallelBuilder {
 public:
  ParallelBuilder(const WorkCellDesc& desc, const DeviceDesc& device,
                  const std::vector<FrameId>& ids, const rw::kinematics::FrameTree& tree,
                  common::DiagnosticSink& sink)
      : d_(desc), device_(device), ids_(ids), tree_(tree), sink_(sink) {}

  std::optional<ParallelStructure> run();

 private:
  const FrameDesc& frameAt(std::size_t k) const {
    return d_.frames[static_cast<std::size_t>(device_.frames[k])];
  }
  FrameId id(int descIndex) const { return ids_[static_cast<std::size_t>(descIndex)]; }
  bool startsNewChain(std::size_t k, const std::string& chainName) const;
  void splitChains();
  std::optional<std::vector<int>> joinChains(const ChainsDesc& leg);
  void addLeg(Junction& junction, const Origin& origin, std::vector<std::string> names,
              const std::vector<int>& frames);
  void checkPassiveJoints(const ParallelStructure& structure);

  const WorkCellDesc& d_;
  const DeviceDesc& device_;
  const std::vector<FrameId>& ids_;
  const rw::kinematics::FrameTree& tree_;
  common::DiagnosticSink& sink_;
  std::vector<Chain> chains_;
  std::map<std::string, std::size_t> byName_;  // the last chain of each name, as in RobWork
  bool ok_ = true;
};

// RobWork's rule: a frame that hangs on the previous frame continues the chain, unless a
// later frame also hangs on that previous frame (a branch), or the frames that follow in one
// run leave the current SerialChain for another one.
bool ParallelBuilder::startsNewChain(std::size_t k, const std::string& chainName) const {
  const std::size_t n = device_.frames.size();
  if (frameAt(k).parent != frameAt(k - 1).name) return true;
  for (std::size_t j = k + 1; j < n && k >= 2; ++j) {
    if (frameAt(j).parent == frameAt(k - 1).name) return true;
  }
  if (chainName.empty()) return false;
  for (std::size_t j = k + 1; j < n; ++j) {
    if (frameAt(j).parent != frameAt(j - 1).name) break;
    if (frameAt(j).chain == chainName || frameAt(j).chain.empty()) break;
    return true;
  }
  return false;
}

void ParallelBuilder::splitChains() {
  std::map<std::string, int> placed{{frameAt(0).name, device_.frames[0]}};
  Chain chain{"", {device_.frames[0]}};
  std::string chainName;
  for (std::size_t k = 1; k < device_.frames.size(); ++k) {
    const FrameDesc& f = frameAt(k);
    if (startsNewChain(k, chainName)) {
      chain.name = chainName;
      byName_[chainName] = chains_.size();
      chains_.push_back(std::move(chain));
      chainName.clear();
      const auto parent = placed.find(f.parent);
      if (parent == placed.end()) {
        sink_.error(f.origin.location, f.origin.element +
                                           ": in a ParallelDevice a frame hangs on an earlier "
                                           "frame of the same device; \"" +
                                           f.parent + "\" is not one");
        ok_ = false;
        chain = Chain{"", {device_.frames[k]}};
      } else {
        chain = Chain{"", {parent->second, device_.frames[k]}};
      }
    } else {
      chain.frames.push_back(device_.frames[k]);
      if (!f.chain.empty()) chainName = f.chain;
    }
    placed[f.name] = device_.frames[k];
  }
  chain.name = chainName;
  byName_[chainName] = chains_.size();
  chains_.push_back(std::move(chain));
}

std::optional<std::vector<int>> ParallelBuilder::joinChains(const ChainsDesc& leg) {
  std::vector<int> frames;
  for (const std::string& name : leg.names) {
    const auto it = byName_.find(name);
    if (it == byName_.end()) {
      std::string known;
      for (const auto& [chainName, index] : byName_) {
        if (!chainName.empty()) known += (known.empty() ? "" : ", ") + chainName;
      }
      sink_.error(leg.origin.location, leg.origin.element + ": unknown SerialChain \"" + name +
                                           "\"; the chains of device \"" + device_.name +
                                           "\" are: " + (known.empty() ? "(none)" : known));
      return std::nullopt;
    }
    const std::vector<int>& next = chains_[it->second].frames;
    std::size_t first = 0;
    if (!frames.empty()) {
      if (frames.back() != next.front()) {
        sink_.error(leg.origin.location,
                    leg.origin.element + ": chain \"" + name + "\" starts at frame \"" +
                        d_.frames[static_cast<std::size_t>(next.front())].name + "\", not at \"" +
                        d_.frames[static_cast<std::size_t>(frames.back())].name +
                        "\" where the leg so far ends; the chains of a leg follow each other");
        return std::nullopt;
      }
      first = 1;
    }
    frames.insert(frames.end(), next.begin() + static_cast<std::ptrdiff_t>(first), next.end());
  }
  return frames;
}

void ParallelBuilder::addLeg(Junction& junction, const Origin& origin,
                             std::vector<std::string> names, const std::vector<int>& frames) {
  ParallelLeg leg{std::move(names), id(frames.front()), id(frames.back())};
  const auto frameName = [&](FrameId f) { return "\"" + tree_.frame(f).name() + "\""; };
  if (frames.size() < 2) {
    sink_.error(origin.location, origin.element + ": the leg is only the frame " +
                                     frameName(leg.start) + "; a leg needs frames below its start");
    ok_ = false;
    return;
  }
  if (!junction.legs.empty() && leg.start != junction.legs.front().start) {
    sink_.error(origin.location, origin.element + ": the leg starts at frame " +
                                     frameName(leg.start) + ", the junction's first leg at " +
                                     frameName(junction.legs.front().start) +
                                     "; the legs of a junction start at one frame");
    ok_ = false;
    return;
  }
  for (const ParallelLeg& other : junction.legs) {
    if (other.end == leg.end) {
      sink_.error(origin.location, origin.element + ": the leg ends at frame " +
                                       frameName(leg.end) +
                                       " like an earlier leg of the junction; the legs end at "
                                       "different frames, which the junction holds together");
      ok_ = false;
      return;
    }
  }
  junction.legs.push_back(std::move(leg));
}

// Every passive joint must move some leg (itself or a joint depending on it), or nothing
// determines its value.
void ParallelBuilder::checkPassiveJoints(const ParallelStructure& structure) {
  std::vector<char> moved(tree_.size(), 0);
  for (const Junction& junction : structure.junctions) {
    for (const ParallelLeg& leg : junction.legs) {
      for (FrameId f = leg.end; f != leg.start && f.valid(); f = tree_.frame(f).parent()) {
        const auto& dependency = tree_.frame(f).dependency();
        moved[static_cast<std::size_t>((dependency ? dependency->owner : f).index)] = 1;
      }
    }
  }
  for (const int i : device_.frames) {
    const rw::kinematics::Frame& frame = tree_.frame(id(i));
    if (!frame.isJoint() || frame.isDependent() || !frame.isPassive()) continue;
    if (moved[static_cast<std::size_t>(frame.id().index)]) continue;
    const Origin& origin = d_.frames[static_cast<std::size_t>(i)].origin;
    sink_.error(origin.location, origin.element +
                                     ": a passive joint on no leg of a <Junction>; nothing "
                                     "determines its value (make it active or add its chain "
                                     "to a junction)");
    ok_ = false;
  }
}

std::optional<ParallelStructure> ParallelBuilder::run() {
  ParallelStructure structure;
  for (const int i : device_.frames) structure.frames.push_back(id(i));
  splitChains();
  if (!ok_) return std::nullopt;
  if (device_.junctions.empty()) {
    // RobWork's older form: one junction whose legs are all the chains.
    Junction junction;
    for (const Chain& chain : chains_) {
      std::vector<std::string> names;
      if (!chain.name.empty()) names.push_back(chain.name);
      addLeg(junction, device_.origin, std::move(names), chain.frames);
    }
    if (ok_ && junction.legs.size() < 2) {
      sink_.error(device_.origin.location,
                  device_.origin.element +
                      ": a ParallelDevice without <Junction> closes one loop over its serial "
                      "chains, and this one has a single chain");
      return std::nullopt;
    }
    structure.junctions.push_back(std::move(junction));
  }
  for (const JunctionDesc& jd : device_.junctions) {
    Junction junction;
    for (const ChainsDesc& leg : jd.legs) {
      const auto frames = joinChains(leg);
      if (!frames) {
        ok_ = false;
        continue;
      }
      addLeg(junction, leg.origin, leg.names, *frames);
    }
    structure.junctions.push_back(std::move(junction));
  }
  if (ok_) checkPassiveJoints(structure);
  if (!ok_) return std::nullopt;
  return structure;
}

}  // namespace

std::optional<ParallelStructure> buildParallelStructure(const WorkCellDesc& desc,
                                                        const DeviceDesc& device,
                                                        const std::vector<FrameId>& ids,
                                                        const rw::kinematics::FrameTree& tree,
                                                        common::DiagnosticSink& sink) {
  return ParallelBuilder(desc, device, ids, tree, sink).run();
}

}  // namespace rw::loaders::detail
