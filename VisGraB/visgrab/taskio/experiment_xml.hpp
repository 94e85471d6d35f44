#pragma once

#include <filesystem>
#include <string_view>

#include "rw/common/xml_tree.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::taskio {

/// Reads the original VisGraB experiment XML (visgrab-formats.md §2) from `text`, named `file`
/// in messages. Per <experiment>: method = the experiment id, scene = sceneInfo/sceneID (both
/// trimmed); per grasp element, in document order, one request with id = the element's own id
/// attribute (unique within the experiment; the original's VisGraBID was "<experiment>.<id>",
/// i.e. method + "." + id, but used the pre-shape id for pre-shape grasps):
/// <grasp> and <preshapegrasp> -> kRaw (pose in metres; q_open/q_closed/tau_max from the grasp or
/// from the experiment's <gripper><preshape>, whose name is kept in `preshape`), <contactgrasp>
/// -> kContacts (positions in metres, directions and approach as written).
/// Stricter than the original, one diagnostic per rejected grasp (the rest is read): non-unit
/// quaternion (|q| off by more than 1e-3), non-orthonormal rotmatrix (entries of R^T R - I above
/// 1e-3) or reflection, wrong number counts, bad numbers, q_closed/maxtau lengths unlike q_open,
/// unknown pre-shape, contacts other than 2 or 3, zero directions, duplicate ids. When both
/// <quaternion> and <rotmatrix> are given the later one wins (as in the original). Namespace
/// prefixes are ignored on every element. An experiment without id or sceneID gives one
/// diagnostic and its grasps are skipped. @throws rw::common::LoadError for malformed XML or
/// a root other than <visgrab>.
GraspFileContents parseExperimentXml(std::string_view text, const std::filesystem::path& file);

/// parseExperimentXml on the content of `file`. @throws rw::common::LoadError.
GraspFileContents readExperimentXml(const std::filesystem::path& file);

namespace detail {
/// The requests of an already parsed <visgrab> root, appended to `out`.
void experimentsFromElement(const rw::common::XmlElement& root, const std::string& file,
                            GraspFileContents& out);
}  // namespace detail

}  // namespace visgrab::taskio
