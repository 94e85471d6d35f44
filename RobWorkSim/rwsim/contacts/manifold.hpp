#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rwsim/contacts/contact_detector.hpp"

/// Reduction of contact candidates to small, stable manifolds (internal to rwsim_contacts).
namespace rwsim::contacts::detail {

/// Candidates whose depths differ by less than this (m) count as equally deep; the tie is
/// broken by position, so a flat resting contact keeps the same points from step to step.
inline constexpr double kDepthTie = 1e-6;
/// Contacts whose normals are within this angle (rad) of a cluster's first normal join it
/// (RobWork's normal clustering, 10 degrees).
inline constexpr double kClusterAngle = 10.0 * rw::math::kDeg2Rad;

/// Reusable buffers of the reduction (grown once, then no allocation).
struct ReduceScratch {
  /// Candidates projected on the contact plane.
  std::vector<Eigen::Vector2d> planar;
  /// Indices of all candidates.
  std::vector<std::int32_t> all;
  /// Convex hull of all candidates (the only ones worth choosing after the first).
  std::vector<std::int32_t> outline;
  /// Hull of a trial choice.
  std::vector<std::int32_t> trial;
  /// Scores of the candidates in a choice.
  std::vector<double> scores;
  /// The chosen points but one.
  std::vector<std::int32_t> others;
  /// Whether each candidate is within kDepthTie of the deepest.
  std::vector<char> tiedDeepest;
  /// Chosen candidates in order of choice.
  std::vector<std::int32_t> chosen;
  /// Convex hull (counter-clockwise) of the chosen candidates, as indices.
  std::vector<std::int32_t> hull;
  /// Scratch for the hull computation.
  std::vector<std::int32_t> sorted;
  /// Cluster of each point.
  std::vector<std::int32_t> cluster;
  /// First normal of each cluster.
  std::vector<rw::math::Vector3D> clusterNormal;
  /// Sum of normals of each cluster.
  std::vector<rw::math::Vector3D> clusterSum;
  /// Points of the cluster being reduced.
  std::vector<ContactPoint> members;
};

/// Appends to `out` at most `maxPoints` of `points` (one touching region whose normals are
/// close to `normal`): the deepest (depth ties within kDepthTie broken by position), the one
/// farthest from it, then each time the one that adds most area to the polygon of those
/// chosen, then swaps that grow the area further (the first point only for one as deep). Points
/// that add no extent (duplicates, collinear extras) are dropped.
void reduceManifold(std::span<const ContactPoint> points, const rw::math::Vector3D& normal,
                    int maxPoints, std::vector<ContactPoint>& out, ReduceScratch& scratch);

/// Groups `points` by normal (kClusterAngle around each cluster's first normal, clusters in
/// order of their first point) and appends each group reduced by reduceManifold().
void clusterAndReduce(std::span<const ContactPoint> points, int maxPoints,
                      std::vector<ContactPoint>& out, ReduceScratch& scratch);

}  // namespace rwsim::contacts::detail
