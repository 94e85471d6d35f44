#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "rw/math/types.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/importers/grasp_importers.hpp"

namespace visgrab::importers {

/// The grasp file formats `visgrab import` reads (docs/grasp-format.md, "Importing grasps").
enum class ImportFormat {
  kGraspnet,         ///< graspnetAPI's GraspGroup .npy, in the scene's camera frame
  kContactGraspnet,  ///< Contact-GraspNet's grasps as a plain .npz, in the camera frame
  kAcronym,          ///< ACRONYM's .h5 or GraspGen's .json, in the object's mesh frame
};

/// The format's name on the command line: "graspnet", "contact-graspnet", "acronym".
const char* importFormatName(ImportFormat format);

/// The format called `name`, if any.
std::optional<ImportFormat> importFormatFromName(std::string_view name);

/// Where a file's grasps go: the importers' context and the pose of the frame they are given in.
struct ImportTarget {
  /// Scene, method, the hand's jaw frame and name.
  ImportContext context;
  /// The frame of the file's grasps in the scene's world (table) frame: the rectified left
  /// camera (graspnet, contact-graspnet: OpenCV axes, x right, y down, z forward) or the scaled
  /// mesh frame of the scene's object (acronym).
  rw::math::Transform3D X_W_frame = rw::math::Transform3D::Identity();
};

/// The target of `format`'s grasps in scene `scene` of `db` for `hand` (method: the format's
/// name when empty). The camera is the scene's calibration's rectifiedLeftPose(); the mesh frame
/// of an acronym scene is its recorded source's frame (SceneEntry::source, as `visgrab db
/// from-acronym` records it).
/// @throws ImportError when the hand declares no jaw frame, the scene has no calibration
/// (camera formats) or records no source (acronym); UnknownSceneError for an unknown scene.
ImportTarget importTarget(ImportFormat format, const database::Database& db,
                          const std::string& scene, const grasp::HandGraspSetup& hand,
                          const std::string& method);

/// The id of the one scene of `db` made from a file named as `file` (its name without folders,
/// SceneEntry::source). @throws ImportError when none or several are.
std::string sceneMadeFrom(const database::Database& db, const std::filesystem::path& file);

/// Imports `file` of `format` for `target` (the importers of grasp_importers.hpp).
/// @throws ImportError for a file that cannot be read as a whole.
ImportResult importGraspFile(ImportFormat format, const std::filesystem::path& file,
                             const ImportTarget& target);

}  // namespace visgrab::importers
