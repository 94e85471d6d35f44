#pragma once

#include <filesystem>
#include <functional>
#include <vector>

#include "visgrab/analysis/showcase.hpp"
#include "visgrab/results/trial_record.hpp"

namespace visgrab::view {

/// How the report's pictures are drawn.
struct ReportPictureOptions {
  /// Worker threads (each with its own offscreen context); the pictures do not depend on it.
  int threads = 1;
  /// The scene data folder whose protocols/ holds the named trial protocols: a run made with a
  /// protocol other than the lift is drawn with DATA/protocols/NAME.xml when that has the
  /// recorded hash (results::replayProtocol); empty: such runs get no pictures.
  std::filesystem::path data;
  /// Size of one of a strip's three panels, pixels.
  int width = 320;
  /// See width.
  int height = 240;
  /// Called after each picture with (done, total), from the worker threads (serialised).
  std::function<void(int done, int total)> progress;
};

/// Draws each showcase's trial as graspStrip into reportDir/images/ (named after its column,
/// group and role) and sets its image, simulating the trial again with the run's database, grasp
/// files, hand, engine and protocol as its run.csv records them (RunResults::sources; the
/// protocol from options.data). Where that is impossible (an older run without sources, a moved
/// database, a protocol not found, no OpenGL) the showcase gets a note instead, and the report
/// is written without that picture.
void drawShowcases(std::vector<analysis::Showcase>& showcases,
                   const std::vector<results::RunResults>& runs,
                   const std::filesystem::path& reportDir, const ReportPictureOptions& options);

/// drawShowcases as an analysis::ShowcaseDrawer for analysis::writeReport.
analysis::ShowcaseDrawer showcaseDrawer(ReportPictureOptions options);

}  // namespace visgrab::view
