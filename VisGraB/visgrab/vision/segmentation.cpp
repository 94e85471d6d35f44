#include "visgrab/vision/segmentation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <utility>

namespace visgrab::vision {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Principal axes of points: their mean and the covariance's eigenvectors, smallest
// eigenvalue first (column 0: the normal of the least-squares plane; column 2: the longest
// extent).
struct PrincipalAxes {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

PrincipalAxes principalAxes(const std::vector<Eigen::Vector3d>& pts) {
  PrincipalAxes pa;
  for (const auto& p : pts) pa.mean += p;
  pa.mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - pa.mean) * (p - pa.mean).transpose();
  pa.axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors();
  return pa;
}

// Least-squares plane of points: (unit normal with z >= 0, offset).
std::pair<Eigen::Vector3d, double> planeFit(const std::vector<Eigen::Vector3d>& pts) {
  const PrincipalAxes pa = principalAxes(pts);
  Eigen::Vector3d n = pa.axes.col(0);
  if (n.z() < 0) n = -n;
  return {n, n.dot(pa.mean)};
}

// Smallest union-find: parent links, path halving; the root is the smallest index.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      auto& p = parent[static_cast<std::size_t>(i)];
      p = parent[static_cast<std::size_t>(p)];
      i = p;
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent[static_cast<std::size_t>(b)] = a;
  }
};

// In-plane orthonormal basis (e1, e2) of the plane with normal n.
std::pair<Eigen::Vector3d, Eigen::Vector3d> planeBasis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d seed =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (seed - seed.dot(n) * n).normalized();
  return {e1, n.cross(e1)};
}

// Value at quantile q (0..1) of `values` (reordered).
double quantile(std::vector<double>& values, double q) {
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Centroid, top and footprint of a cluster. Top and footprint ignore the outermost 1 % / 2 % of
// the points: a few mismatched pixels at an occluding edge must not stretch them.
void describeCluster(const OrganizedCloud& cloud, const TablePlane& table, Cluster& c) {
  const auto [e1, e2] = planeBasis(table.normal);
  c.centroid.setZero();
  std::vector<double> heights;
  for (int i : c.cells) {
    const Eigen::Vector3d p = cloud.point(i);
    c.centroid += p;
    heights.push_back(table.height(p));
  }
  c.centroid /= static_cast<double>(c.cells.size());
  c.top = quantile(heights, 0.99);
  const Eigen::Vector2d mid(c.centroid.dot(e1), c.centroid.dot(e2));
  std::vector<double> spread;
  std::vector<cv::Point2f> footprint;
  for (int i : c.cells) {
    const Eigen::Vector3d p = cloud.point(i);
    spread.push_back((Eigen::Vector2d(p.dot(e1), p.dot(e2)) - mid).norm());
  }
  std::vector<double> sorted = spread;
  const double limit = quantile(sorted, 0.98);
  for (std::size_t k = 0; k < c.cells.size(); ++k) {
    if (spread[k] > limit) continue;
    const Eigen::Vector3d p = cloud.point(c.cells[k]);
    footprint.emplace_back(static_cast<float>(p.dot(e1)), static_cast<float>(p.dot(e2)));
  }
  const cv::RotatedRect rect = cv::minAreaRect(footprint);
  c.footprint = Eigen::Vector2d(std::max(rect.size.width, rect.size.height),
                                std::min(rect.size.width, rect.size.height));
  c.centre = table.offset * table.normal + rect.center.x * e1 + rect.center.y * e2 +
             0.5 * c.top * table.normal;
}

}  // namespace

TablePlane fitTablePlane(const OrganizedCloud& cloud, const SegmentationOptions& options) {
  std::vector<Eigen::Vector3d> all;
  for (int i = 0; i < cloud.size(); ++i) {
    if (cloud.valid(i)) all.push_back(cloud.point(i));
  }
  std::vector<Eigen::Vector3d> sample;
  const std::size_t stride = static_cast<std::size_t>(std::max(1, options.ransacStride));
  for (std::size_t i = 0; i < all.size(); i += stride) sample.push_back(all[i]);
  if (sample.size() < 3) throw std::runtime_error("table plane: fewer than 3 points with depth");

  std::mt19937 rng(options.ransacSeed);
  const double cosTilt = std::cos(options.maxTableTilt * kDeg);
  const auto n = static_cast<std::uint32_t>(sample.size());
  double bestScore = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d bestNormal = Eigen::Vector3d::Zero();
  double bestOffset = 0.0;
  for (int it = 0; it < options.ransacIterations; ++it) {
    // Plain modulo: the same draws with every standard library.
    const auto& a = sample[rng() % n];
    const auto& b = sample[rng() % n];
    const auto& c = sample[rng() % n];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    const double len = normal.norm();
    if (len < 1e-9) continue;
    normal /= len;
    if (normal.z() < 0) normal = -normal;
    if (normal.z() < cosTilt) continue;
    const double offset = normal.dot(a);
    int inliers = 0, below = 0;
    for (const auto& p : sample) {
      const double h = normal.dot(p) - offset;
      if (std::abs(h) <= options.planeThreshold)
        ++inliers;
      else if (h < -options.belowMargin)
        ++below;
    }
    const double score = inliers - options.belowPenalty * below;
    if (score > bestScore) {
      bestScore = score;
      bestNormal = normal;
      bestOffset = offset;
    }
  }
  TablePlane plane;
  if (bestNormal.isZero() || bestScore < options.minTableInliers) {
    // The table is not seen well enough (a plain cloth, little texture): the calibrated table
    // frame is the best estimate there is.
    plane.fromCalibration = true;
    for (const auto& p : all) plane.inliers += std::abs(plane.height(p)) <= options.planeThreshold;
    return plane;
  }
  // Refit twice on the inliers among all points.
  plane.normal = bestNormal;
  plane.offset = bestOffset;
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<Eigen::Vector3d> inliers;
    for (const auto& p : all) {
      if (std::abs(plane.height(p)) <= options.planeThreshold) inliers.push_back(p);
    }
    plane.inliers = static_cast<int>(inliers.size());
    if (pass == 2 || inliers.size() < 3) break;
    std::tie(plane.normal, plane.offset) = planeFit(inliers);
  }
  return plane;
}

SceneSegmentation segmentScene(OrganizedCloud cloud, const SegmentationOptions& options) {
  SceneSegmentation s;
  s.table = fitTablePlane(cloud, options);
  s.cloud = std::move(cloud);
  const OrganizedCloud& pc = s.cloud;
  const int W = pc.width, H = pc.height, N = pc.size();
  const TablePlane& table = s.table;
  auto at = [](auto& v, int i) -> auto& { return v[static_cast<std::size_t>(i)]; };

  // Object cells: above the table, below maxObjectHeight, inside the workspace.
  std::vector<char> object(static_cast<std::size_t>(N), 0);
  for (int i = 0; i < N; ++i) {
    if (!pc.valid(i)) continue;
    const Eigen::Vector3d p = pc.point(i);
    const double h = table.height(p);
    if (h < options.minObjectHeight || h > options.maxObjectHeight) continue;
    const Eigen::Vector3d onPlane = p - h * table.normal - table.offset * table.normal;
    if (onPlane.norm() > options.workspaceRadius) continue;
    at(object, i) = 1;
  }
  // Untextured cells (guessed depths) count only next to textured object cells, within
  // untexturedReach: they fill an object's plain areas but cannot chain into long tentacles
  // along a plain table.
  {
    std::vector<char> keep(static_cast<std::size_t>(N), 0);
    const int reach = options.untexturedReach;
    for (int i = 0; i < N; ++i) {
      if (!at(object, i) || !at(pc.textured, i)) continue;
      const int r = i / W, c = i % W;
      for (int rr = std::max(0, r - reach); rr <= std::min(H - 1, r + reach); ++rr) {
        for (int cc = std::max(0, c - reach); cc <= std::min(W - 1, c + reach); ++cc)
          at(keep, rr * W + cc) = 1;
      }
    }
    for (int i = 0; i < N; ++i) at(object, i) = at(object, i) && at(keep, i);
  }

  // Connected pieces: 8-connected components with a distance limit between neighbours.
  DisjointSets sets(N);
  const double link2 = options.clusterLink * options.clusterLink;
  auto close = [&](int a, int b) {
    return (at(pc.points, a) - at(pc.points, b)).squaredNorm() < link2;
  };
  for (int r = 0; r < H; ++r) {
    for (int c = 0; c < W; ++c) {
      const int i = r * W + c;
      if (!at(object, i)) continue;
      const int nbr[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
      for (const auto& d : nbr) {
        const int rr = r + d[0], cc = c + d[1];
        if (rr >= H || cc < 0 || cc >= W) continue;
        const int j = rr * W + cc;
        if (at(object, j) && close(i, j)) sets.unite(i, j);
      }
    }
  }
  // Pieces that are objects: large enough, high enough, and mostly textured (a flat image
  // region, such as the wall behind the table, gets depths SGBM guessed).
  std::vector<int> pieceOf(static_cast<std::size_t>(N), -1);
  {
    std::vector<std::vector<int>> groups(static_cast<std::size_t>(N));
    for (int i = 0; i < N; ++i) {
      if (at(object, i)) at(groups, sets.find(i)).push_back(i);
    }
    int pieces = 0;
    for (auto& g : groups) {
      if (static_cast<int>(g.size()) < options.minClusterCells) continue;
      double top = 0.0;
      int textured = 0;
      for (int i : g) {
        top = std::max(top, table.height(pc.point(i)));
        textured += at(pc.textured, i);
      }
      if (top < options.minClusterTop) continue;
      if (textured < options.minTexturedFraction * static_cast<double>(g.size())) continue;
      for (int i : g) at(pieceOf, i) = pieces;
      ++pieces;
    }
  }

  // Normals by PCA over a window of the same piece; "flatness" orders the patch seeds.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  s.normals.assign(static_cast<std::size_t>(N), Eigen::Vector3f(nan, nan, nan));
  std::vector<double> curvature(static_cast<std::size_t>(N), 1.0);
  const double hood2 = options.normalNeighbourhood * options.normalNeighbourhood;
  const int R = options.normalRadius;
  for (int i = 0; i < N; ++i) {
    const int k = at(pieceOf, i);
    if (k < 0) continue;
    const int r = i / W, c = i % W;
    const Eigen::Vector3d p = pc.point(i);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    int count = 0;
    for (int rr = std::max(0, r - R); rr <= std::min(H - 1, r + R); ++rr) {
      for (int cc = std::max(0, c - R); cc <= std::min(W - 1, c + R); ++cc) {
        const int j = rr * W + cc;
        if (at(pieceOf, j) != k) continue;
        const Eigen::Vector3d q = pc.point(j) - p;
        if (q.squaredNorm() > hood2) continue;
        sum += q;
        outer += q * q.transpose();
        ++count;
      }
    }
    if (count < 6) continue;
    const Eigen::Vector3d mean = sum / count;
    const Eigen::Matrix3d cov = outer / count - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Vector3d normal = eig.eigenvectors().col(0);
    if (normal.dot(pc.viewpoint - p) < 0) normal = -normal;
    at(s.normals, i) = normal.cast<float>();
    const double trace = eig.eigenvalues().sum();
    at(curvature, i) = trace > 0 ? eig.eigenvalues()(0) / trace : 1.0;
  }

  // Patches: region growing from the flattest cells over 4-neighbours of the same piece.
  std::vector<int> patchOf(static_cast<std::size_t>(N), -1);
  std::vector<int> seeds;
  for (int i = 0; i < N; ++i) {
    if (at(pieceOf, i) >= 0 && !std::isnan(at(s.normals, i).x())) seeds.push_back(i);
  }
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](int a, int b) { return at(curvature, a) < at(curvature, b); });
  const double cosPatch = std::cos(options.patchAngle * kDeg);
  std::vector<char> seeded(static_cast<std::size_t>(N), 0);
  const int four[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  auto neighbour = [&](int i, const int d[2]) {
    const int rr = i / W + d[0], cc = i % W + d[1];
    return rr < 0 || rr >= H || cc < 0 || cc >= W ? -1 : rr * W + cc;
  };
  std::vector<std::vector<int>> regions;
  for (int seed : seeds) {
    if (at(patchOf, seed) != -1 || at(seeded, seed)) continue;
    const int k = at(pieceOf, seed);
    const Eigen::Vector3f seedNormal = at(s.normals, seed);
    const int id = static_cast<int>(regions.size());
    std::vector<int> region{seed};
    at(patchOf, seed) = id;
    for (std::size_t q = 0; q < region.size(); ++q) {
      const int i = region[q];
      for (const auto& d : four) {
        const int j = neighbour(i, d);
        if (j < 0 || at(patchOf, j) != -1 || at(pieceOf, j) != k) continue;
        const Eigen::Vector3f& nj = at(s.normals, j);
        if (std::isnan(nj.x()) || nj.dot(seedNormal) < cosPatch || !close(i, j)) continue;
        at(patchOf, j) = id;
        region.push_back(j);
      }
    }
    if (static_cast<int>(region.size()) < options.minPatchCells) {
      for (int i : region) {
        at(patchOf, i) = -1;
        at(seeded, i) = 1;
      }
      continue;
    }
    regions.push_back(std::move(region));
  }
  // Each region's plane (its cells in increasing order), normal towards the camera.
  std::vector<PrincipalAxes> regionAxes;
  std::vector<Eigen::Vector3d> regionNormal;
  for (auto& region : regions) {
    std::sort(region.begin(), region.end());
    std::vector<Eigen::Vector3d> pts;
    pts.reserve(region.size());
    for (int i : region) pts.push_back(pc.point(i));
    regionAxes.push_back(principalAxes(pts));
    Eigen::Vector3d n = regionAxes.back().axes.col(0);
    if (n.dot(pc.viewpoint - regionAxes.back().mean) < 0) n = -n;
    regionNormal.push_back(n);
  }

  // Every cell of a piece joins the patch nearest to it over the grid (breadth first).
  std::vector<int> regionOf = patchOf;
  {
    std::vector<int> queue;
    for (int i = 0; i < N; ++i) {
      if (at(regionOf, i) >= 0) queue.push_back(i);
    }
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int i = queue[q];
      for (const auto& d : four) {
        const int j = neighbour(i, d);
        if (j < 0 || at(regionOf, j) != -1 || at(pieceOf, j) != at(pieceOf, i) || !close(i, j))
          continue;
        at(regionOf, j) = at(regionOf, i);
        queue.push_back(j);
      }
    }
  }

  // Objects are convex here, so two patches whose meeting is concave belong to two objects
  // that touch (after the idea of locally convex connected patches): across each meeting of
  // two regions, (n_i - n_j) . (p_a - p_b) / |p_a - p_b| is > 0 where the surface bends
  // outwards and < 0 where it bends inwards.
  std::map<std::pair<int, int>, std::pair<double, int>> meetings;
  for (int a = 0; a < N; ++a) {
    const int i = at(regionOf, a);
    if (i < 0) continue;
    for (const auto& d : four) {
      const int b = neighbour(a, d);
      if (b < 0) continue;
      const int j = at(regionOf, b);
      if (j <= i || !close(a, b)) continue;
      const Eigen::Vector3d ab = pc.point(a) - pc.point(b);
      const double len = ab.norm();
      if (len < 1e-9) continue;
      auto& m = meetings[{i, j}];
      m.first += (at(regionNormal, i) - at(regionNormal, j)).dot(ab) / len;
      m.second += 1;
    }
  }
  DisjointSets objects(static_cast<int>(regions.size()));
  for (const auto& [pair, m] : meetings) {
    // A meeting of a few cells says little (noise at an occluding edge); it joins nothing.
    if (m.second < options.minMeetingCells) continue;
    if (m.first / m.second >= -options.concavity) objects.unite(pair.first, pair.second);
  }

  // A small part cut off a piece by concave meetings is more likely a feature of one object (a
  // jug's handle) than a second object: it rejoins the part of its piece it meets longest.
  {
    std::vector<int> regionCells(regions.size(), 0), pieceCells;
    for (int i = 0; i < N; ++i) {
      if (at(regionOf, i) >= 0) ++at(regionCells, at(regionOf, i));
      const int k = at(pieceOf, i);
      if (k >= 0) {
        if (k >= static_cast<int>(pieceCells.size()))
          pieceCells.resize(static_cast<std::size_t>(k) + 1, 0);
        ++at(pieceCells, k);
      }
    }
    std::map<int, int> groupCells;
    for (std::size_t r = 0; r < regions.size(); ++r)
      groupCells[objects.find(static_cast<int>(r))] += regionCells[r];
    for (const auto& [root, cells] : groupCells) {
      const int piece = at(pieceOf, at(regions, root).front());
      if (cells >= options.minPartFraction * at(pieceCells, piece)) continue;
      int best = -1, longest = 0;
      for (const auto& [pair, m] : meetings) {
        const int a = objects.find(pair.first), b = objects.find(pair.second);
        if (a == b || (a != objects.find(root) && b != objects.find(root))) continue;
        if (m.second >= options.minMeetingCells && m.second > longest) {
          longest = m.second;
          best = a == objects.find(root) ? b : a;
        }
      }
      if (best >= 0) objects.unite(root, best);
    }
  }

  // Clusters: the cells of each group of convexly connected regions.
  {
    std::map<int, std::vector<int>> groups;
    for (int i = 0; i < N; ++i) {
      if (at(regionOf, i) >= 0) groups[objects.find(at(regionOf, i))].push_back(i);
    }
    for (auto& [root, cells] : groups) {
      if (static_cast<int>(cells.size()) < options.minClusterCells) continue;
      Cluster c;
      c.cells = std::move(cells);
      s.clusters.push_back(std::move(c));
    }
  }
  std::stable_sort(s.clusters.begin(), s.clusters.end(), [](const Cluster& a, const Cluster& b) {
    return a.cells.size() > b.cells.size();
  });
  s.clusterOf.assign(static_cast<std::size_t>(N), -1);
  for (std::size_t k = 0; k < s.clusters.size(); ++k) {
    for (int i : s.clusters[k].cells) at(s.clusterOf, i) = static_cast<int>(k);
    describeCluster(pc, table, s.clusters[k]);
  }

  // Patches of the clusters: by cluster, then largest first.
  std::vector<int> order;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    if (at(s.clusterOf, regions[r].front()) >= 0) order.push_back(static_cast<int>(r));
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const int ka = at(s.clusterOf, at(regions, a).front());
    const int kb = at(s.clusterOf, at(regions, b).front());
    if (ka != kb) return ka < kb;
    return at(regions, a).size() > at(regions, b).size();
  });
  s.patchOf.assign(static_cast<std::size_t>(N), -1);
  for (int r : order) {
    SurfacePatch patch;
    patch.cells = std::move(at(regions, r));
    patch.cluster = at(s.clusterOf, patch.cells.front());
    patch.centroid = at(regionAxes, r).mean;
    patch.normal = at(regionNormal, r);
    patch.axis1 = at(regionAxes, r).axes.col(2);
    patch.axis2 = patch.normal.cross(patch.axis1);
    for (int i : patch.cells) at(s.patchOf, i) = static_cast<int>(s.patches.size());
    s.patches.push_back(std::move(patch));
  }

  // Patch boundaries.
  for (std::size_t id = 0; id < s.patches.size(); ++id) {
    SurfacePatch& patch = s.patches[id];
    for (int i : patch.cells) {
      bool onBoundary = false, objectEnds = false;
      for (const auto& d : four) {
        const int j = neighbour(i, d);
        if (j >= 0 && at(s.patchOf, j) == static_cast<int>(id)) continue;
        onBoundary = true;
        if (j < 0 || at(s.clusterOf, j) != patch.cluster || !close(i, j)) objectEnds = true;
      }
      if (!onBoundary) continue;
      patch.boundary.push_back(i);
      patch.edge.push_back(objectEnds);
    }
  }
  return s;
}

}  // namespace visgrab::vision
