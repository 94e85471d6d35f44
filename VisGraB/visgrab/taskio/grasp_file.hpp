#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "visgrab/request/grasp_request.hpp"

namespace visgrab::taskio {

/// What a grasp file yields: the grasps that were read and one diagnostic per grasp that was not.
struct GraspFileContents {
  /// The good grasps, in file order.
  std::vector<grasp::GraspRequest> requests;
  /// One error per rejected grasp (file:line:col and what was expected); the others are read.
  std::vector<rw::common::Diagnostic> rejected;
  /// Warnings that did not cost a grasp (ignored elements, projected rotations, ...).
  std::vector<rw::common::Diagnostic> warnings;
};

/// The formats readGraspFile tells apart.
enum class GraspFileFormat {
  kRwTask,      ///< RobWork's CartesianTask XML (root <CartesianTask>)
  kExperiment,  ///< the original VisGraB experiment XML (root <visgrab>)
  kGraspList,   ///< the project's plain grasp list (docs/grasp-format.md)
};

/// The format of `text`: XML by root element, anything that does not start with '<' a grasp
/// list. @throws rw::common::LoadError for XML with another root or malformed XML.
GraspFileFormat detectGraspFileFormat(std::string_view text, const std::filesystem::path& file);

/// Reads a grasp file of any of the three formats. An rwtask file needs a root String property
/// `SceneID` (as VisGraB wrote it); its method is the file name without `.rwtask.xml`, `.task.xml`
/// or `.xml`, its targets become raw grasps (toGraspRequests); sub-tasks whose refframe is not
/// WORLD are rejected (one diagnostic each). @throws rw::common::LoadError for a whole-file
/// problem: unreadable file, malformed XML, unknown XML root, rwtask without SceneID or with a
/// malformed value.
GraspFileContents readGraspFile(const std::filesystem::path& file);

/// readGraspFile for every regular file in `folder` (not recursive; names starting with '.' are
/// skipped), in order of file name; contents are concatenated. @throws rw::common::LoadError
/// for the first file that cannot be read, or if `folder` is not a folder.
GraspFileContents readGraspFolder(const std::filesystem::path& folder);

/// readGraspFolder for each folder and readGraspFile for each file of `paths`, concatenated in
/// that order. @throws rw::common::LoadError as they do.
GraspFileContents readGraspSources(const std::vector<std::filesystem::path>& paths);

}  // namespace visgrab::taskio
