#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "visgrab/vision/stereo.hpp"

namespace visgrab::vision {

/// Settings of the table plane, the object clusters and the surface patches.
struct SegmentationOptions {
  /// RANSAC iterations of the table plane.
  int ransacIterations = 400;
  /// Every how many valid cloud cells RANSAC samples (speed).
  int ransacStride = 3;
  /// Seed of RANSAC's own generator (fixed: same input, same plane).
  std::uint32_t ransacSeed = 20120601;
  /// A point is on the plane if within this distance (m).
  double planeThreshold = 0.006;
  /// Largest angle (deg) between the table plane's normal and the calibrated table frame's z:
  /// the calibration says roughly where the table is; RANSAC says exactly.
  double maxTableTilt = 15.0;
  /// Points this far below a candidate plane (m) count against it: the table is the lowest
  /// large plane, so a box's top face loses to it even on a plain, texture-poor table.
  double belowMargin = 0.02;
  /// Weight of each point below a candidate plane against its inliers.
  double belowPenalty = 2.0;
  /// Fewer sampled inliers (less the penalty) than this: the table is not seen well enough and
  /// the calibrated table frame's z = 0 plane is used instead.
  int minTableInliers = 500;
  /// Object points are at least this high above the table (m) ...
  double minObjectHeight = 0.008;
  /// ... at most this high ...
  double maxObjectHeight = 0.4;
  /// ... and within this radius (m) of the table frame's origin, in the plane.
  double workspaceRadius = 0.25;
  /// Neighbouring cells join one cluster when their points are closer than this (m).
  double clusterLink = 0.012;
  /// Clusters with fewer cells are noise.
  int minClusterCells = 150;
  /// Clusters whose highest point is lower than this (m) are noise too (mismatches on the
  /// table); the flattest object lying down is about 3 cm high.
  double minClusterTop = 0.02;
  /// Untextured cells are object cells only within this many cells of a textured object cell.
  int untexturedReach = 2;
  /// Pieces whose cells are less than this fraction textured are not objects (the wall behind
  /// the table gets depths SGBM guessed from its smoothness term).
  double minTexturedFraction = 0.5;
  /// Two patches that meet with a concave bend larger than this (mean of (n_i - n_j) . u over
  /// their meeting, u the unit step across it; about the sine of the bend) belong to two touching
  /// objects: the objects are convex.
  double concavity = 0.15;
  /// Two regions join only if they meet along at least this many neighbouring cell pairs
  /// (about 1.5 cm at cloudStep 2): a few pairs are noise where one object occludes another.
  int minMeetingCells = 8;
  /// A part of a piece cut off by concave meetings with fewer than this fraction of the piece's
  /// cells rejoins the part it meets longest: a feature of one object (a jug's handle), not a
  /// second object.
  double minPartFraction = 0.25;
  /// Half side (cells) of the window the normals are fitted in.
  int normalRadius = 3;
  /// Points farther than this (m) from a cell's point do not enter its normal.
  double normalNeighbourhood = 0.015;
  /// A cell joins a growing patch if its normal is within this angle (deg) of the patch seed's.
  double patchAngle = 20.0;
  /// Patches with fewer cells are dropped.
  int minPatchCells = 60;
};

/// The table plane: points p with normal . p = offset; normal points up (away from the table,
/// towards the camera side).
struct TablePlane {
  /// Unit normal in the table frame.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// Plane offset (m).
  double offset = 0.0;
  /// Cloud points within planeThreshold of the final plane.
  int inliers = 0;
  /// True if RANSAC found no good plane and this is the calibrated table frame's z = 0.
  bool fromCalibration = false;
  /// Height of p above the plane (m).
  double height(const Eigen::Vector3d& p) const { return normal.dot(p) - offset; }
};

/// One object as the cloud shows it: a connected, convexly joined set of points above the table.
struct Cluster {
  /// Cloud cells of the cluster, in increasing order.
  std::vector<int> cells;
  /// Mean of its points (table frame).
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  /// Estimate of the object's centre: the centre of the smallest rectangle around the points'
  /// footprint on the table (the 98 % nearest the centroid), at half the top height. Less biased
  /// towards the camera than the centroid (only the front of an object is seen).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  /// Height of its highest points above the table (m; the 99th percentile).
  double top = 0.0;
  /// Sides of the footprint rectangle (m), longer first.
  Eigen::Vector2d footprint = Eigen::Vector2d::Zero();
};

/// A smooth piece of an object's visible surface.
struct SurfacePatch {
  /// Index of its cluster.
  int cluster = -1;
  /// Cloud cells of the patch, in increasing order.
  std::vector<int> cells;
  /// Cells of the patch with a 4-neighbour that is not in it, in increasing order.
  std::vector<int> boundary;
  /// For each boundary cell: true if the surface ends there (the neighbour outside is not on the
  /// object or lies more than clusterLink behind/in front), false if the object's surface goes
  /// on (a crease to another patch).
  std::vector<bool> edge;
  /// Mean of its points.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  /// Unit normal (plane fit), towards the camera.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// Unit in-plane axes: longest extent first (principal axes of the points).
  Eigen::Vector3d axis1 = Eigen::Vector3d::UnitX(), axis2 = Eigen::Vector3d::UnitY();
};

/// Everything the baseline sees in one scene.
struct SceneSegmentation {
  /// The cloud (table frame).
  OrganizedCloud cloud;
  /// The fitted table plane.
  TablePlane table;
  /// Per cloud cell: cluster index, or -1.
  std::vector<int> clusterOf;
  /// Objects, largest first.
  std::vector<Cluster> clusters;
  /// Per cloud cell: unit normal (NaN where none was fitted).
  std::vector<Eigen::Vector3f> normals;
  /// Per cloud cell: patch index, or -1.
  std::vector<int> patchOf;
  /// Surface patches, cluster by cluster, largest first within a cluster.
  std::vector<SurfacePatch> patches;
};

/// The table plane by RANSAC over the cloud, then a least-squares refit on its inliers.
/// Candidates must be within maxTableTilt of the table frame's z axis; each scores its
/// inliers less belowPenalty per point more than belowMargin below it. Falls back to the
/// calibrated table plane (fromCalibration) when the best candidate scores below
/// minTableInliers. @throws std::runtime_error if the cloud has fewer than 3 points.
TablePlane fitTablePlane(const OrganizedCloud& cloud, const SegmentationOptions& options);

/// Table plane; pieces (connected components of the above-table points over the image grid,
/// mostly textured); normals (PCA over a window); surface patches (region growing on the
/// normals), every cell of a piece joined to its nearest patch; object clusters = patches
/// connected by convex meetings (concave meetings separate touching objects).
SceneSegmentation segmentScene(OrganizedCloud cloud, const SegmentationOptions& options);

}  // namespace visgrab::vision
