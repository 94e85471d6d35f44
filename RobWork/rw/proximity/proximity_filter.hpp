#pragma once

#include <compare>
#include <string>
#include <vector>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/models/setups.hpp"
#include "rw/models/workcell.hpp"
#include "rw/proximity/name_pattern.hpp"

namespace rw::proximity {

/// An unordered pair of frames, stored with first < second.
struct FramePair {
  /// The frame with the smaller id.
  rw::kinematics::FrameId first;
  /// The frame with the larger id.
  rw::kinematics::FrameId second;
  /// Pairs order by first, then second.
  friend constexpr auto operator<=>(const FramePair&, const FramePair&) = default;
};

/// The pair of `a` and `b` in canonical order. Precondition: a != b.
inline FramePair makeFramePair(rw::kinematics::FrameId a, rw::kinematics::FrameId b) {
  return a < b ? FramePair{a, b} : FramePair{b, a};
}

/// For every frame of `tree`, the number of its static group: frames connected through fixed
/// frames only share a group; every joint, movable frame and DAF starts a new group.
std::vector<int> staticFrameGroups(const rw::kinematics::FrameTree& tree);

/// The frame pairs that proximity queries check, computed once as RobWork's
/// BasicFilterStrategy does: all pairs of frames with collision geometry (if useIncludeAll),
/// minus pairs in one static group (if useExcludeStaticPairs), then each rule in order removes
/// (Exclude) or adds (Include) the pairs of distinct frames it matches.
class ProximityFilter {
 public:
  /// The pairs of `workcell` under its own proximitySetup().
  /// @throws std::invalid_argument if a REGEX pattern does not compile.
  explicit ProximityFilter(const rw::models::WorkCell& workcell);
  /// The pairs of `workcell` under `setup`.
  /// @throws std::invalid_argument if a REGEX pattern does not compile.
  ProximityFilter(const rw::models::WorkCell& workcell, const rw::models::ProximitySetup& setup);

  /// The pairs, sorted by frame id.
  const std::vector<FramePair>& pairs() const { return pairs_; }
  /// True when the pair of `a` and `b` is checked.
  bool contains(rw::kinematics::FrameId a, rw::kinematics::FrameId b) const;

 private:
  std::vector<FramePair> pairs_;
};

}  // namespace rw::proximity
