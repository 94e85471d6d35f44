#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "visgrab/request/grasp_request.hpp"
#include "visgrab/vision/segmentation.hpp"

namespace visgrab::vision {

/// The paper's surface-based Elementary Grasping Actions (§4, Figure 5).
enum class GraspType {
  kS2Ega1,  ///< "s2EGA1": two fingers encompassing a surface, at opposite ends of it
  kS2Ega3,  ///< "s2EGA3": two fingers pinching a surface at its boundary, front and back
  kS3Ega1,  ///< "s3EGA1": three fingers encompassing a surface
};

/// The three types in report order.
inline constexpr std::array<GraspType, 3> kGraspTypes = {GraspType::kS2Ega1, GraspType::kS2Ega3,
                                                         GraspType::kS3Ega1};

/// "s2EGA1", "s2EGA3", "s3EGA1": the method names in grasp files and reports.
const char* graspTypeName(GraspType type);
/// The type called `name` (as graspTypeName writes it), if any.
std::optional<GraspType> graspTypeFromName(std::string_view name);

/// Settings of the grasp synthesis. Defaults suit the SDH (reach of its fingers); another hand
/// changes the width limits.
struct GraspOptions {
  /// Largest number of grasps per scene and type (the best ones).
  int perType = 20;
  /// Encompassing grasps put their contacts this far (m) beyond the surface, along its back
  /// normal, at the object's outermost visible extent there: the fingers wrap round the
  /// surface's boundary.
  double wrapDepth = 0.015;
  /// Where the object visibly bulges further out below wrapDepth (a lying cylinder), the
  /// contact goes down to the bulge, at most this deep (m).
  double maxWrapDepth = 0.045;
  /// Pinch grasps touch the surface this far (m) inside its boundary ...
  double pinchInset = 0.01;
  /// ... and its back behind it: the back is not seen, so the object is taken to be as thick
  /// there as its visible points reach behind the surface (within pinchInset of the pinch,
  /// e.g. a box's side face below its top), plus pinchMargin, and at least pinchThickness (m).
  double pinchThickness = 0.02;
  /// See pinchThickness (m).
  double pinchMargin = 0.005;
  /// Two-finger encompassing grasps: smallest and largest distance between the contacts (m).
  double minWidth = 0.02;
  /// See minWidth.
  double maxWidth = 0.12;
  /// Width the ranking prefers (m): well inside the hand's opening.
  double preferredWidth = 0.06;
  /// Three-finger grasps: smallest and largest distance between two contacts (m).
  double minSpan = 0.025;
  /// See minSpan.
  double maxSpan = 0.13;
  /// Three-finger grasps across a patch: distance (m) between the two fingers opposite the
  /// thumb (the SDH's fingers 2 and 3 at spread 0: their bases 38.1 mm from the palm centre,
  /// 120 deg apart, 2 x 38.1 mm x sin 60 deg = 66 mm).
  double fingerGap = 0.066;
  /// Contacts lower than this above the table (m) are not used (the finger would hit it).
  double minContactHeight = 0.012;
  /// Contacts lower than this (m) lower the grasp's rank.
  double clearHeight = 0.03;
  /// Boundary points within this distance (m) of a grasp line or plane belong to it.
  double lateralTolerance = 0.006;
  /// Grasp axes per patch for the two-finger encompassing grasp (over 180 deg).
  int axes = 12;
  /// Boundary directions per patch for the pinch and the three-finger grasps (over 360 deg).
  int directions = 24;
  /// Two grasps of a type are the same when their approaches are within 15 deg and every
  /// contact of one is within this distance (m) of a contact of the other.
  double distinct = 0.012;
};

/// A grasp hypothesis with its rank.
struct CandidateGrasp {
  /// Its type.
  GraspType type = GraspType::kS2Ega1;
  /// 2 or 3 desired contacts (table frame).
  std::vector<grasp::DesiredContact> contacts;
  /// Direction of travel of the hand (unit).
  Eigen::Vector3d approach = -Eigen::Vector3d::UnitZ();
  /// Rank: higher is better (see ega.cpp for the terms).
  double score = 0.0;
  /// The patch it was made from.
  int patch = -1;
};

/// All grasps of the three types on the scene's patches, best first within each type, at most
/// options.perType per type after dropping near-duplicates, types in kGraspTypes order.
/// Deterministic.
std::vector<CandidateGrasp> generateGrasps(const SceneSegmentation& scene,
                                           const GraspOptions& options);

}  // namespace visgrab::vision
