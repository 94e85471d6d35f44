#include "rw/proximity/proximity_filter.hpp"

#include <algorithm>

namespace rw::proximity {

using rw::kinematics::FrameId;
using rw::kinematics::FrameTree;
using rw::kinematics::FrameType;

namespace {

// Pair membership as a square matrix of flags; only entries (i < j) are used.
class PairSet {
 public:
  explicit PairSet(std::size_t frames) : n_(frames), flags_(frames * frames, 0) {}
  void set(std::size_t a, std::size_t b, bool value) {
    flags_[std::min(a, b) * n_ + std::max(a, b)] = value ? 1 : 0;
  }
  bool get(std::size_t a, std::size_t b) const { return flags_[a * n_ + b] != 0; }
  std::vector<FramePair> sorted() const {
    std::vector<FramePair> pairs;
    for (std::size_t i = 0; i < n_; ++i) {
      for (std::size_t j = i + 1; j < n_; ++j) {
        if (get(i, j)) {
          pairs.push_back(
              {FrameId{static_cast<std::int32_t>(i)}, FrameId{static_cast<std::int32_t>(j)}});
        }
      }
    }
    return pairs;
  }

 private:
  std::size_t n_;
  std::vector<char> flags_;
};

std::vector<std::size_t> framesMatching(const FrameTree& tree, const NamePattern& pattern) {
  std::vector<std::size_t> matching;
  for (std::size_t i = 0; i < tree.size(); ++i) {
    if (pattern.matches(tree.frames()[i].name())) matching.push_back(i);
  }
  return matching;
}

void applyRule(const FrameTree& tree, const rw::models::ProximityRule& rule, PairSet& set) {
  const std::vector<std::size_t> a = framesMatching(tree, NamePattern(rule.patternA));
  const std::vector<std::size_t> b = framesMatching(tree, NamePattern(rule.patternB));
  for (const std::size_t i : a) {
    for (const std::size_t j : b) {
      if (i != j) set.set(i, j, rule.include);
    }
  }
}

}  // namespace

std::vector<int> staticFrameGroups(const FrameTree& tree) {
  std::vector<int> group(tree.size(), 0);
  int groups = 1;
  for (std::size_t i = 1; i < tree.size(); ++i) {
    const rw::kinematics::Frame& f = tree.frames()[i];
    if (f.type() == FrameType::kFixed && !f.isDaf()) {
      group[i] = group[static_cast<std::size_t>(f.parent().index)];
    } else {
      group[i] = groups++;
    }
  }
  return group;
}

ProximityFilter::ProximityFilter(const rw::models::WorkCell& workcell)
    : ProximityFilter(workcell, workcell.proximitySetup()) {}

ProximityFilter::ProximityFilter(const rw::models::WorkCell& workcell,
                                 const rw::models::ProximitySetup& setup) {
  const FrameTree& tree = workcell.frames();
  PairSet set(tree.size());
  if (setup.useIncludeAll) {
    std::vector<std::size_t> withGeometry;
    for (const rw::models::Object& object : workcell.objects()) {
      if (!object.collision.empty())
        withGeometry.push_back(static_cast<std::size_t>(object.frame.index));
    }
    for (const std::size_t i : withGeometry) {
      for (const std::size_t j : withGeometry) {
        if (i != j) set.set(i, j, true);
      }
    }
  }
  if (setup.useExcludeStaticPairs) {
    const std::vector<int> group = staticFrameGroups(tree);
    for (std::size_t i = 0; i < tree.size(); ++i) {
      for (std::size_t j = i + 1; j < tree.size(); ++j) {
        if (group[i] == group[j]) set.set(i, j, false);
      }
    }
  }
  for (const rw::models::ProximityRule& rule : setup.rules) applyRule(tree, rule, set);
  pairs_ = set.sorted();
}

bool ProximityFilter::contains(FrameId a, FrameId b) const {
  if (a == b) return false;
  return std::binary_search(pairs_.begin(), pairs_.end(), makeFramePair(a, b));
}

}  // namespace rw::proximity
