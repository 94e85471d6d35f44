#pragma once

#include <vector>

#include "rw/geometry/geometry.hpp"

namespace visgrab::objects {

/// Tuning of decomposeConvex.
struct DecompositionOptions {
  /// At most this many pieces.
  int maxPieces = 16;
  /// A part is not cut further once its hull exceeds its own volume by at most this fraction
  /// (or by less than 0.2 % of the whole mesh's volume).
  double concavity = 0.03;
  /// Evenly spaced candidate cut positions per axis inside the part's extent.
  int cutsPerAxis = 15;
};

/// An approximate convex decomposition and what it cost in volume.
struct ConvexDecomposition {
  /// The convex hulls of the parts, closed and wound outwards, in the mesh's frame.
  std::vector<rw::geometry::TriMesh> pieces;
  /// Volume of the input mesh, m^3.
  double meshVolume = 0.0;
  /// Sum of the pieces' volumes, m^3 (>= meshVolume up to overlaps of the hulls).
  double piecesVolume = 0.0;
  /// Parts left out because their points span no volume (slivers of less than 1e-3 of the
  /// mesh's volume, cut from thin walls).
  int flatPartsDropped = 0;
};

/// Splits the solid bounded by a closed, outward-wound mesh into convex pieces by recursive
/// plane cuts: the part whose hull exceeds its volume most is cut next, by the axis-aligned
/// plane (x, y or z; DecompositionOptions::cutsPerAxis positions each, plus the part's vertex
/// coordinates when there are at most twice as many distinct ones) that leaves the least
/// hull-minus-part volume in its two halves, until every part is within
/// DecompositionOptions::concavity of its hull or maxPieces is reached; each part is replaced by
/// its hull (Qhull). Parts are exact: the cut faces are closed implicitly (each cut is capped by a
/// fan over its oriented cross-section segments, which integrates exactly), so no polygon is
/// triangulated. Deterministic.
/// @throws std::invalid_argument if the mesh has no positive volume.
ConvexDecomposition decomposeConvex(const rw::geometry::TriMesh& mesh,
                                    const DecompositionOptions& options = {});

}  // namespace visgrab::objects
