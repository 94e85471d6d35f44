#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/analysis/analysis.hpp"
#include "visgrab/analysis/showcase.hpp"
#include "visgrab/results/trial_record.hpp"

namespace visgrab::analysis {

/// Colour (CSS hex) of an outcome in the plots; kNoGraspColour for "no grasp suggested".
std::string_view outcomeColour(rwsim::trial::GraspOutcome outcome);
/// Grey of the "no grasp suggested" share (paper Figure 6).
inline constexpr std::string_view kNoGraspColour = "#a6a6a6";
/// Legend text of an outcome ("stable grasp", "object slipped", ...; paper §2.4).
std::string_view outcomeLegend(rwsim::trial::GraspOutcome outcome);

/// `text` with &, <, >, " and ' replaced by entities (for HTML and SVG).
std::string escapeHtml(std::string_view text);

/// Writes the CSV tables into `outDir`: distribution.csv (Figure 6), quality.csv (Table 1),
/// attempts.csv (Figure 7), first_success.csv (Table 2), objects.csv (Tables 3-4), with the
/// intervals also success.csv (overall success rates) and comparisons.csv (method against
/// method), with repeats robust.csv; each atomically. With intervals each estimate column X is
/// followed by X_ci_low and X_ci_high. quality.csv and first_success.csv also give the paper's
/// values (paperValues()), empty where it has none. Undefined values (NaN) are empty fields.
/// @throws std::runtime_error.
void writeCsvTables(const Analysis& analysis, const std::filesystem::path& outDir);

/// The report as Markdown (with intervals: the overall success rates and method against method
/// first; robust rates with repeats; tables of all five analyses, definitions in short, every
/// estimate with its interval; Tables 1 and 2 with the paper's values beside the methods named
/// like its grasp types, and the note on comparing), then the showcases that have a picture, as
/// image links.
std::string markdownReport(const Analysis& analysis, const std::vector<Showcase>& showcases = {});

/// The report as one HTML page (inline SVG plots); the showcases' pictures, if any, are the only
/// files it refers to (images/ next to it).
std::string htmlReport(const Analysis& analysis, const std::vector<Showcase>& showcases = {});

/// Analyses `runs` and writes the CSV tables, report.md and report.html into `outDir`. With a
/// `drawer`, the showcases (chooseShowcases) are drawn first and shown in both reports.
/// @throws std::runtime_error if a file cannot be written, std::invalid_argument for bad options.
void writeReport(const std::vector<results::RunResults>& runs, const std::filesystem::path& outDir,
                 const AnalysisOptions& options = {}, const ShowcaseDrawer& drawer = {});

}  // namespace visgrab::analysis
