#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "visgrab/analysis/analysis.hpp"
#include "visgrab/results/trial_record.hpp"

namespace visgrab::analysis {

/// A trial the report shows as a picture: for each compared method and each of the four
/// conditions (textured/plain x single/double), its best, a typical and a failed grasp.
struct Showcase {
  /// Index into Analysis::columns.
  std::size_t column = 0;
  /// Index of the column's run in the runs analysed.
  std::size_t run = 0;
  /// The condition group (ConditionGroup::key, e.g. "textured-single-all") and its heading.
  std::string groupKey;
  /// See groupKey.
  std::string groupName;
  /// "best" (the held grasp of highest Q_lift, ties by Q_GWS, then first), "typical" (the
  /// held grasp of median Q_lift, the best left out when there are others) or "failure" (the
  /// first grasp of the most frequent failing outcome).
  std::string role;
  /// The trial.
  results::TrialRecord trial;
  /// The picture, relative to the report folder (e.g. "images/....png"); empty: not drawn.
  std::string image;
  /// Why there is no picture, or a remark about it (empty if none).
  std::string note;
};

/// The trials to show, in report order: columns, then textured single, textured double, plain
/// single, plain double, then best, typical, failure (each when the group has such a trial).
/// Deterministic: trials are taken in the runs' canonical order.
std::vector<Showcase> chooseShowcases(const Analysis& analysis,
                                      const std::vector<results::RunResults>& runs);

/// "best: plain/single/cocacola/01 s2EGA1-03 (rank 3), stable, Q_lift 0.934, Q_GWS 0.4210,
/// Q_GWS,unit 0.0121" ("–" for a value the trial lacks).
std::string showcaseCaption(const Showcase& showcase);

/// Draws pictures for showcases: sets Showcase::image (a file it wrote below the report folder)
/// or Showcase::note for each. Given to writeReport by a caller that can render.
using ShowcaseDrawer = std::function<void(std::vector<Showcase>& showcases,
                                          const std::vector<results::RunResults>& runs,
                                          const std::filesystem::path& reportDir)>;

}  // namespace visgrab::analysis
