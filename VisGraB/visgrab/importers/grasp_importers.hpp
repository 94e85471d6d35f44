#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rw/math/types.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/importers/nd_array.hpp"
#include "visgrab/request/grasp_request.hpp"

namespace visgrab::importers {

/// The Franka Panda hand's finger-pad centre on its base frame's z axis, m (franka_description's
/// TCP; Contact-GraspNet's gripper_depth; ACRONYM's grasps).
inline constexpr double kPandaPadDepth = 0.1034;
/// The Franka Panda hand's full opening, m (ACRONYM's grasps are always fully open).
inline constexpr double kPandaOpening = 0.08;
/// Largest entry of |R^T R - I| a file's rotation may have (float32 files reach about 1e-7); a
/// rotation within it is made exactly orthonormal (nearest rotation), one beyond it is rejected.
inline constexpr double kRotationTolerance = 1e-4;

/// One grasp of a file that was not imported.
struct ImportRejection {
  /// The file, as given.
  std::string file;
  /// The grasp's index in the file (its id).
  std::size_t index = 0;
  /// What is wrong and what was expected.
  std::string message;
  /// "FILE: grasp INDEX: MESSAGE".
  std::string format() const;
};

/// What an importer gives: the grasps it imported and one rejection per grasp it did not. A bad
/// grasp costs only itself (as in the grasp list); a bad file throws ImportError.
struct ImportResult {
  /// Jaw grasps (GraspKind::kJaw) in file order: id the index in the file ("0", "1", ...),
  /// the method, the score when the format has one, sourceFile the file.
  std::vector<grasp::GraspRequest> grasps;
  /// One per grasp that was not imported, in file order.
  std::vector<ImportRejection> rejected;
};

/// What every importer needs besides the file.
struct ImportContext {
  /// The scene id the grasps are for.
  std::string sceneId;
  /// The method name of the grasps (the analyses group by it).
  std::string method;
  /// The hand's jaw frame: its stroke bounds the width; its tipDepth places GraspNet grasps.
  grasp::JawFrame jaw;
  /// The hand's name, for messages.
  std::string hand;
};

/// graspnetAPI's GraspGroup array (N x 17: score, width, height, depth, rotation row-major 3x3,
/// translation, object id) in the camera frame whose pose in the world is `X_W_camera`. Jaw
/// frame: z = the rotation's column 0 (approach), x = column 1 (closing), origin
/// t + (depth - jaw.tipDepth) column 0 (docs/grasp-format.md, "graspnet").
/// @throws ImportError naming `file` for another shape.
ImportResult importGraspnetArray(const NdArray& array, const std::string& file,
                                 const rw::math::Transform3D& X_W_camera,
                                 const ImportContext& context);

/// importGraspnetArray on the .npy `file`. @throws ImportError.
ImportResult importGraspnet(const std::filesystem::path& file,
                            const rw::math::Transform3D& X_W_camera, const ImportContext& context);

/// Contact-GraspNet's grasps: `grasps` N x 4 x 4 (the Panda hand's base frame in the camera
/// frame, +z approach, +x closing), `scores` N, optional `widths` N (the predicted opening; the
/// Panda's full 0.08 m when absent). Jaw frame: X_cam_hand Translation(0, 0, 0.1034).
/// @throws ImportError naming `file` and the array for another shape.
ImportResult importContactGraspnetArrays(const NdArray& grasps, const NdArray& scores,
                                         const std::optional<NdArray>& widths,
                                         const std::string& file,
                                         const rw::math::Transform3D& X_W_camera,
                                         const ImportContext& context);

/// The plain .npz `file` of Contact-GraspNet's grasps: arrays `grasps`, `scores`, optional
/// `widths` and `segments` (N; checked, not kept). @throws ImportError naming the file and the
/// array: missing, another shape, or an object array (pickled dicts, as Contact-GraspNet's
/// inference script saves them), whose message shows the line of numpy that writes the plain
/// form.
ImportResult importContactGraspnet(const std::filesystem::path& file,
                                   const rw::math::Transform3D& X_W_camera,
                                   const ImportContext& context);

/// ACRONYM's transforms (N x 4 x 4: the Panda hand's base frame in the scaled mesh's frame),
/// placed through `X_W_mesh`: X_W_jaw = X_W_mesh X_mesh_hand Translation(0, 0, 0.1034), width
/// 0.08 m (checked against the hand's stroke). No score.
ImportResult importAcronymTransforms(const NdArray& transforms, const std::string& file,
                                     const rw::math::Transform3D& X_W_mesh,
                                     const ImportContext& context);

/// importAcronymTransforms on an ACRONYM .h5 (`grasps/transforms`) or GraspGen's .json
/// (`grasps.transforms`), told apart by the file's first bytes. @throws ImportError.
ImportResult importAcronym(const std::filesystem::path& file, const rw::math::Transform3D& X_W_mesh,
                           const ImportContext& context);

/// The rotation of a grasp read from a file, made exactly orthonormal; nullopt with `why` set
/// when it is not a rotation within kRotationTolerance (or has a non-finite entry).
std::optional<rw::math::Rotation3D> checkedRotation(const Eigen::Matrix3d& R, std::string& why);

}  // namespace visgrab::importers
