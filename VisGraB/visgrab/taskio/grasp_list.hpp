#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "visgrab/request/grasp_request.hpp"
#include "visgrab/taskio/grasp_file.hpp"

namespace visgrab::taskio {

/// Reads the plain grasp list (docs/grasp-format.md) from `text`, named `file` in messages.
/// Every bad line gives one diagnostic (file:line:col of the bad field) in `rejected`; the good
/// lines are read. Never throws for bad content.
GraspFileContents parseGraspList(std::string_view text, const std::filesystem::path& file);

/// parseGraspList on the content of `file`. @throws rw::common::LoadError if unreadable.
GraspFileContents readGraspList(const std::filesystem::path& file);

/// The grasp list text for `requests` (a comment header, then one line per grasp; numbers in
/// shortest round-trip form, rotations as unit quaternions with w >= 0).
/// @throws std::invalid_argument if an id, scene, method or pre-shape name is empty or holds a
/// comma, '#', a line break or surrounding blanks, or a kContacts grasp has not 2 or 3 contacts.
std::string formatGraspList(const std::vector<grasp::GraspRequest>& requests);

/// Writes formatGraspList(requests) to `file`. @throws std::invalid_argument as
/// formatGraspList, std::runtime_error if it cannot be written.
void writeGraspList(const std::vector<grasp::GraspRequest>& requests,
                    const std::filesystem::path& file);

/// The kind called `name` in files ("raw", "preshape", "pose_q", "contacts", "jaw"), if any.
std::optional<grasp::GraspKind> kindFromName(std::string_view name);

}  // namespace visgrab::taskio
