#pragma once

#include <string>
#include <utility>
#include <vector>

namespace rw::models {

/// RobWork's old-format collision setup (reference §1.7), frame names already scoped.
struct CollisionSetup {
  /// Unordered frame pairs never checked.
  std::vector<std::pair<std::string, std::string>> excludePairs;
  /// Frames marked volatile.
  std::vector<std::string> volatileFrames;
  /// `<ExcludeStaticPairs/>` was present.
  bool excludeStaticPairs = false;
};

/// One rule of a proximity setup: wildcard patterns (`*`, `?`) or, prefixed "REGEX", a regex.
struct ProximityRule {
  /// Pattern for one frame of the pair.
  std::string patternA;
  /// Pattern for the other frame.
  std::string patternB;
  /// Include (true) or exclude (false).
  bool include = false;
};

/// The merged proximity setup of a workcell (reference §1.5 step 7, §1.8).
struct ProximitySetup {
  /// Start from all pairs of frames with geometry.
  bool useIncludeAll = true;
  /// Remove pairs rigidly connected to each other.
  bool useExcludeStaticPairs = false;
  /// Rules applied in order.
  std::vector<ProximityRule> rules;
};

}  // namespace rw::models
