#pragma once

#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"

/// Readers of RobWorkSim's file formats.
namespace rwsim::loaders {

/// How a dynamic workcell is loaded besides its file.
struct DynamicWorkCellLoadOptions {
  /// Included files read from other files (rw::loaders::IncludeRedirects), for the Includes of
  /// the dynamic workcell and those of the workcell it names alike; empty: none.
  rw::loaders::IncludeRedirects includeRedirects;
};

/// Loads a RobWorkSim dynamic workcell file (`.dwc.xml`, reference §2) and the workcell it
/// names (relative to the file's folder, loaded with rw::loaders::loadWorkCell).
/// RobWork's leniencies are kept and reported as warnings: mismatched closing tags are read as
/// closing the innermost open element; Include paths are relative to the top-level file's
/// folder (and, if not found there, relative to the including file); duplicate materials and
/// friction pairs with unknown materials are ignored; Property type "double" is read as float;
/// a RigidBody without Integrator is accepted. Elements this project does not simulate
/// (sensors, constraints, kinematic devices, suction cups, other controllers) are skipped with a
/// warning. EstimateInertia gives the inertia about the centre of mass (not RobWork's
/// about-the-origin tensor, Appendix A.10). Warnings, also those of the workcell, are appended
/// to `warnings` if given, also when the load fails.
/// @throws rw::common::LoadError with every diagnostic found (what(): the errors, each at
/// file:line:column).
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> loadDynamicWorkCell(
    const std::filesystem::path& file, std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Same as loadDynamicWorkCell, with `options` (Include redirects).
/// @throws rw::common::LoadError as loadDynamicWorkCell; a redirect whose replacement cannot be
/// read is an error at the redirected Include (file:line).
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> loadDynamicWorkCell(
    const std::filesystem::path& file, const DynamicWorkCellLoadOptions& options,
    std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Same as loadDynamicWorkCell, reading the top-level XML from `xml`. Relative paths (the
/// workcell, Includes) resolve against the folder of `virtualFile`; diagnostics name it.
/// @throws rw::common::LoadError listing every error found.
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> loadDynamicWorkCellFromString(
    std::string_view xml, const std::filesystem::path& virtualFile,
    std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Same as loadDynamicWorkCellFromString, with the text of the workcell it names given too
/// (instead of read from that file; relative paths in it resolve against that file's folder and
/// messages name it): a scene composed in memory, e.g. with another hand.
/// @throws rw::common::LoadError listing every error found.
std::unique_ptr<rwsim::dynamics::DynamicWorkCell> loadDynamicWorkCellFromStrings(
    std::string_view xml, std::string_view workcellXml, const std::filesystem::path& virtualFile,
    std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// Checks a dynamic workcell file as loadDynamicWorkCell would and returns every error and
/// warning in the order found. Never throws for bad input.
std::vector<rw::common::Diagnostic> checkDynamicWorkCell(const std::filesystem::path& file);

}  // namespace rwsim::loaders
