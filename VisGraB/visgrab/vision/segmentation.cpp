#include "visgrab/vision/segmentation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <optional>
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

// Element i of a per-cell (or per-region) vector.
template <class Vector>
auto& at(Vector& v, int i) {
  return v[static_cast<std::size_t>(i)];
}

// Smallest union-find: parent links, path halving; the root is the smallest index.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i) {
    while (at(parent, i) != i) {
      auto& p = at(parent, i);
      p = at(parent, p);
      i = p;
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    at(parent, b) = a;
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

// The 4-neighbourhood: up, down, left, right as (rows, columns).
constexpr int kFour[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};

// The cloud's grid with the neighbour and link tests the steps share.
struct Grid {
  Grid(const OrganizedCloud& pc, const SegmentationOptions& options)
      : cloud(pc),
        width(pc.width),
        height(pc.height),
        size(pc.size()),
        link2(options.clusterLink * options.clusterLink) {}

  // Cell i moved by d (rows, columns), or -1 outside the grid.
  int neighbour(int i, const int d[2]) const {
    const int rr = i / width + d[0], cc = i % width + d[1];
    return rr < 0 || rr >= height || cc < 0 || cc >= width ? -1 : rr * width + cc;
  }
  // True when the points of cells a and b are closer than clusterLink.
  bool close(int a, int b) const {
    return (at(cloud.points, a) - at(cloud.points, b)).squaredNorm() < link2;
  }
  // A per-cell vector filled with `value`.
  template <class T>
  std::vector<T> cells(T value) const {
    return std::vector<T>(static_cast<std::size_t>(size), value);
  }

  const OrganizedCloud& cloud;
  int width;
  int height;
  int size;
  double link2;
};

// Cells that may show objects: above the table, below maxObjectHeight, inside the workspace.
std::vector<char> objectCandidates(const Grid& g, const TablePlane& table,
                                   const SegmentationOptions& options) {
  std::vector<char> object = g.cells<char>(0);
  for (int i = 0; i < g.size; ++i) {
    if (!g.cloud.valid(i)) continue;
    const Eigen::Vector3d p = g.cloud.point(i);
    const double h = table.height(p);
    if (h < options.minObjectHeight || h > options.maxObjectHeight) continue;
    const Eigen::Vector3d onPlane = p - h * table.normal - table.offset * table.normal;
    if (onPlane.norm() > options.workspaceRadius) continue;
    at(object, i) = 1;
  }
  return object;
}

// Untextured cells (guessed depths) count only next to textured object cells, within `reach`:
// they fill an object's plain areas but cannot chain into long tentacles along a plain table.
void dropFarUntextured(const Grid& g, int reach, std::vector<char>& object) {
  std::vector<char> keep = g.cells<char>(0);
  for (int i = 0; i < g.size; ++i) {
    if (!at(object, i) || !at(g.cloud.textured, i)) continue;
    const int r = i / g.width, c = i % g.width;
    for (int rr = std::max(0, r - reach); rr <= std::min(g.height - 1, r + reach); ++rr) {
      for (int cc = std::max(0, c - reach); cc <= std::min(g.width - 1, c + reach); ++cc)
        at(keep, rr * g.width + cc) = 1;
    }
  }
  for (int i = 0; i < g.size; ++i) at(object, i) = at(object, i) && at(keep, i);
}

// Connected pieces: 8-connected components of object cells, neighbours closer than clusterLink.
DisjointSets linkNeighbours(const Grid& g, const std::vector<char>& object) {
  // Each pair once: right, and the three below.
  constexpr int kForward[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
  DisjointSets sets(g.size);
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const int i = r * g.width + c;
      if (!at(object, i)) continue;
      for (const auto& d : kForward) {
        const int rr = r + d[0], cc = c + d[1];
        if (rr >= g.height || cc < 0 || cc >= g.width) continue;
        const int j = rr * g.width + cc;
        if (at(object, j) && g.close(i, j)) sets.unite(i, j);
      }
    }
  }
  return sets;
}

// A piece is an object when it is large enough, high enough, and mostly textured (a flat image
// region, such as the wall behind the table, gets depths SGBM guessed).
bool isObjectPiece(const Grid& g, const TablePlane& table, const SegmentationOptions& options,
                   const std::vector<int>& cells) {
  if (static_cast<int>(cells.size()) < options.minClusterCells) return false;
  double top = 0.0;
  int textured = 0;
  for (int i : cells) {
    top = std::max(top, table.height(g.cloud.point(i)));
    textured += at(g.cloud.textured, i);
  }
  if (top < options.minClusterTop) return false;
  return !(textured < options.minTexturedFraction * static_cast<double>(cells.size()));
}

// Each cell's object piece (numbered by their smallest cell), or -1.
std::vector<int> objectPieces(const Grid& g, const TablePlane& table,
                              const SegmentationOptions& options, const std::vector<char>& object,
                              DisjointSets& sets) {
  std::vector<std::vector<int>> groups = g.cells(std::vector<int>());
  for (int i = 0; i < g.size; ++i) {
    if (at(object, i)) at(groups, sets.find(i)).push_back(i);
  }
  std::vector<int> pieceOf = g.cells(-1);
  int pieces = 0;
  for (const auto& cells : groups) {
    if (!isObjectPiece(g, table, options, cells)) continue;
    for (int i : cells) at(pieceOf, i) = pieces;
    ++pieces;
  }
  return pieceOf;
}

// A cell's normal (towards the camera) and curvature (smallest eigenvalue / trace).
struct CellNormal {
  Eigen::Vector3f normal;
  double curvature = 1.0;
};

// The normal of cell i by PCA over the cells of its piece within normalRadius (grid) and
// normalNeighbourhood (space); nullopt with fewer than 6 such cells.
std::optional<CellNormal> cellNormal(const Grid& g, const SegmentationOptions& options,
                                     const std::vector<int>& pieceOf, int i) {
  const int k = at(pieceOf, i);
  const double hood2 = options.normalNeighbourhood * options.normalNeighbourhood;
  const int R = options.normalRadius;
  const int r = i / g.width, c = i % g.width;
  const Eigen::Vector3d p = g.cloud.point(i);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  int count = 0;
  for (int rr = std::max(0, r - R); rr <= std::min(g.height - 1, r + R); ++rr) {
    for (int cc = std::max(0, c - R); cc <= std::min(g.width - 1, c + R); ++cc) {
      const int j = rr * g.width + cc;
      if (at(pieceOf, j) != k) continue;
      const Eigen::Vector3d q = g.cloud.point(j) - p;
      if (q.squaredNorm() > hood2) continue;
      sum += q;
      outer += q * q.transpose();
      ++count;
    }
  }
  if (count < 6) return std::nullopt;
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d cov = outer / count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d normal = eig.eigenvectors().col(0);
  if (normal.dot(g.cloud.viewpoint - p) < 0) normal = -normal;
  const double trace = eig.eigenvalues().sum();
  return CellNormal{normal.cast<float>(), trace > 0 ? eig.eigenvalues()(0) / trace : 1.0};
}

// Normals of the piece cells into `normals` (NaN where there is none); returns each cell's
// curvature (1 where there is no normal), the "flatness" that orders the patch seeds.
std::vector<double> estimateNormals(const Grid& g, const SegmentationOptions& options,
                                    const std::vector<int>& pieceOf,
                                    std::vector<Eigen::Vector3f>& normals) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  normals = g.cells(Eigen::Vector3f(nan, nan, nan));
  std::vector<double> curvature = g.cells(1.0);
  for (int i = 0; i < g.size; ++i) {
    if (at(pieceOf, i) < 0) continue;
    const std::optional<CellNormal> n = cellNormal(g, options, pieceOf, i);
    if (!n) continue;
    at(normals, i) = n->normal;
    at(curvature, i) = n->curvature;
  }
  return curvature;
}

// Patch seeds: the piece cells with a normal, flattest first.
std::vector<int> patchSeeds(const Grid& g, const std::vector<int>& pieceOf,
                            const std::vector<Eigen::Vector3f>& normals,
                            const std::vector<double>& curvature) {
  std::vector<int> seeds;
  for (int i = 0; i < g.size; ++i) {
    if (at(pieceOf, i) >= 0 && !std::isnan(at(normals, i).x())) seeds.push_back(i);
  }
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](int a, int b) { return at(curvature, a) < at(curvature, b); });
  return seeds;
}

// The region grown from `seed` over free 4-neighbours of its piece that are linked and whose
// normals are within acos(cosPatch) of the seed's; its cells are marked `id` in patchOf.
std::vector<int> growRegion(const Grid& g, double cosPatch, const std::vector<int>& pieceOf,
                            const std::vector<Eigen::Vector3f>& normals, int seed, int id,
                            std::vector<int>& patchOf) {
  const int k = at(pieceOf, seed);
  const Eigen::Vector3f seedNormal = at(normals, seed);
  std::vector<int> region{seed};
  at(patchOf, seed) = id;
  for (std::size_t q = 0; q < region.size(); ++q) {
    const int i = region[q];
    for (const auto& d : kFour) {
      const int j = g.neighbour(i, d);
      if (j < 0 || at(patchOf, j) != -1 || at(pieceOf, j) != k) continue;
      const Eigen::Vector3f& nj = at(normals, j);
      if (std::isnan(nj.x()) || nj.dot(seedNormal) < cosPatch || !g.close(i, j)) continue;
      at(patchOf, j) = id;
      region.push_back(j);
    }
  }
  return region;
}

// Surface patches: the regions' cells and each cell's region, or -1.
struct Patches {
  std::vector<std::vector<int>> regions;
  std::vector<int> patchOf;
};

// Patches by region growing from the flattest cells; a region smaller than minPatchCells is
// dropped and its cells seed no further region.
Patches growPatches(const Grid& g, const SegmentationOptions& options,
                    const std::vector<int>& pieceOf, const std::vector<Eigen::Vector3f>& normals,
                    const std::vector<double>& curvature) {
  Patches out;
  out.patchOf = g.cells(-1);
  std::vector<char> seeded = g.cells<char>(0);
  const double cosPatch = std::cos(options.patchAngle * kDeg);
  for (int seed : patchSeeds(g, pieceOf, normals, curvature)) {
    if (at(out.patchOf, seed) != -1 || at(seeded, seed)) continue;
    const int id = static_cast<int>(out.regions.size());
    std::vector<int> region = growRegion(g, cosPatch, pieceOf, normals, seed, id, out.patchOf);
    if (static_cast<int>(region.size()) < options.minPatchCells) {
      for (int i : region) {
        at(out.patchOf, i) = -1;
        at(seeded, i) = 1;
      }
      continue;
    }
    out.regions.push_back(std::move(region));
  }
  return out;
}

// The plane of a region: its principal axes and its normal towards the camera.
struct RegionPlane {
  PrincipalAxes axes;
  Eigen::Vector3d normal;
};

// Each region's plane; sorts each region's cells into increasing order first.
std::vector<RegionPlane> regionPlanes(const OrganizedCloud& pc,
                                      std::vector<std::vector<int>>& regions) {
  std::vector<RegionPlane> planes;
  for (auto& region : regions) {
    std::sort(region.begin(), region.end());
    std::vector<Eigen::Vector3d> pts;
    pts.reserve(region.size());
    for (int i : region) pts.push_back(pc.point(i));
    RegionPlane plane{principalAxes(pts), Eigen::Vector3d::Zero()};
    plane.normal = plane.axes.axes.col(0);
    if (plane.normal.dot(pc.viewpoint - plane.axes.mean) < 0) plane.normal = -plane.normal;
    planes.push_back(plane);
  }
  return planes;
}

// Every cell of a piece joins the region nearest to it over the grid (breadth first from the
// patch cells, through linked 4-neighbours of the same piece).
std::vector<int> spreadRegions(const Grid& g, const std::vector<int>& pieceOf,
                               std::vector<int> regionOf) {
  std::vector<int> queue;
  for (int i = 0; i < g.size; ++i) {
    if (at(regionOf, i) >= 0) queue.push_back(i);
  }
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int i = queue[q];
    for (const auto& d : kFour) {
      const int j = g.neighbour(i, d);
      if (j < 0 || at(regionOf, j) != -1 || at(pieceOf, j) != at(pieceOf, i) || !g.close(i, j))
        continue;
      at(regionOf, j) = at(regionOf, i);
      queue.push_back(j);
    }
  }
  return regionOf;
}

// Where two regions (i < j) meet: the summed convexity over their linked neighbouring cells
// and the number of such cell pairs.
using Meetings = std::map<std::pair<int, int>, std::pair<double, int>>;

// Objects are convex here, so two patches whose meeting is concave belong to two objects
// that touch (after the idea of locally convex connected patches): across each meeting of
// two regions, (n_i - n_j) . (p_a - p_b) / |p_a - p_b| is > 0 where the surface bends
// outwards and < 0 where it bends inwards.
Meetings regionMeetings(const Grid& g, const std::vector<int>& regionOf,
                        const std::vector<RegionPlane>& planes) {
  Meetings meetings;
  for (int a = 0; a < g.size; ++a) {
    const int i = at(regionOf, a);
    if (i < 0) continue;
    for (const auto& d : kFour) {
      const int b = g.neighbour(a, d);
      if (b < 0) continue;
      const int j = at(regionOf, b);
      if (j <= i || !g.close(a, b)) continue;
      const Eigen::Vector3d ab = g.cloud.point(a) - g.cloud.point(b);
      const double len = ab.norm();
      if (len < 1e-9) continue;
      auto& m = meetings[{i, j}];
      m.first += (at(planes, i).normal - at(planes, j).normal).dot(ab) / len;
      m.second += 1;
    }
  }
  return meetings;
}

// Regions joined where they meet convexly over at least minMeetingCells cells (a meeting of a
// few cells says little: noise at an occluding edge).
DisjointSets joinConvexMeetings(int regionCount, const Meetings& meetings,
                                const SegmentationOptions& options) {
  DisjointSets objects(regionCount);
  for (const auto& [pair, m] : meetings) {
    if (m.second < options.minMeetingCells) continue;
    if (m.first / m.second >= -options.concavity) objects.unite(pair.first, pair.second);
  }
  return objects;
}

// The group that meets the group of `root` longest (over at least minMeetingCells), or -1.
int longestMeetingGroup(const Meetings& meetings, int root, int minMeetingCells,
                        DisjointSets& objects) {
  int best = -1, longest = 0;
  for (const auto& [pair, m] : meetings) {
    const int a = objects.find(pair.first), b = objects.find(pair.second);
    if (a == b || (a != objects.find(root) && b != objects.find(root))) continue;
    if (m.second >= minMeetingCells && m.second > longest) {
      longest = m.second;
      best = a == objects.find(root) ? b : a;
    }
  }
  return best;
}

// A small part cut off a piece by concave meetings is more likely a feature of one object (a
// jug's handle) than a second object: it rejoins the part of its piece it meets longest.
void rejoinSmallParts(const Grid& g, const SegmentationOptions& options,
                      const std::vector<int>& pieceOf, const std::vector<int>& regionOf,
                      const Patches& patches, const Meetings& meetings, DisjointSets& objects) {
  std::vector<int> regionCells(patches.regions.size(), 0), pieceCells;
  for (int i = 0; i < g.size; ++i) {
    if (at(regionOf, i) >= 0) ++at(regionCells, at(regionOf, i));
    const int k = at(pieceOf, i);
    if (k >= 0) {
      if (k >= static_cast<int>(pieceCells.size()))
        pieceCells.resize(static_cast<std::size_t>(k) + 1, 0);
      ++at(pieceCells, k);
    }
  }
  std::map<int, int> groupCells;
  for (std::size_t r = 0; r < patches.regions.size(); ++r)
    groupCells[objects.find(static_cast<int>(r))] += regionCells[r];
  for (const auto& [root, cells] : groupCells) {
    const int piece = at(pieceOf, at(patches.regions, root).front());
    if (cells >= options.minPartFraction * at(pieceCells, piece)) continue;
    const int best = longestMeetingGroup(meetings, root, options.minMeetingCells, objects);
    if (best >= 0) objects.unite(root, best);
  }
}

// Clusters: the cells of each group of joined regions with at least minClusterCells, largest
// first, described; and each cell's cluster.
void collectClusters(const Grid& g, const SegmentationOptions& options,
                     const std::vector<int>& regionOf, DisjointSets& objects,
                     SceneSegmentation& s) {
  std::map<int, std::vector<int>> groups;
  for (int i = 0; i < g.size; ++i) {
    if (at(regionOf, i) >= 0) groups[objects.find(at(regionOf, i))].push_back(i);
  }
  for (auto& [root, cells] : groups) {
    if (static_cast<int>(cells.size()) < options.minClusterCells) continue;
    Cluster c;
    c.cells = std::move(cells);
    s.clusters.push_back(std::move(c));
  }
  std::stable_sort(s.clusters.begin(), s.clusters.end(), [](const Cluster& a, const Cluster& b) {
    return a.cells.size() > b.cells.size();
  });
  s.clusterOf = g.cells(-1);
  for (std::size_t k = 0; k < s.clusters.size(); ++k) {
    for (int i : s.clusters[k].cells) at(s.clusterOf, i) = static_cast<int>(k);
    describeCluster(s.cloud, s.table, s.clusters[k]);
  }
}

// The regions that belong to clusters: by cluster, then largest first.
std::vector<int> clusterRegionOrder(const std::vector<std::vector<int>>& regions,
                                    const std::vector<int>& clusterOf) {
  std::vector<int> order;
  for (std::size_t r = 0; r < regions.size(); ++r) {
    if (at(clusterOf, regions[r].front()) >= 0) order.push_back(static_cast<int>(r));
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const int ka = at(clusterOf, at(regions, a).front());
    const int kb = at(clusterOf, at(regions, b).front());
    if (ka != kb) return ka < kb;
    return at(regions, a).size() > at(regions, b).size();
  });
  return order;
}

// The patches of the clusters (taking the regions' cells) and each cell's patch.
void collectPatches(const Grid& g, const std::vector<RegionPlane>& planes, Patches& patches,
                    SceneSegmentation& s) {
  s.patchOf = g.cells(-1);
  for (int r : clusterRegionOrder(patches.regions, s.clusterOf)) {
    SurfacePatch patch;
    patch.cells = std::move(at(patches.regions, r));
    patch.cluster = at(s.clusterOf, patch.cells.front());
    patch.centroid = at(planes, r).axes.mean;
    patch.normal = at(planes, r).normal;
    patch.axis1 = at(planes, r).axes.axes.col(2);
    patch.axis2 = patch.normal.cross(patch.axis1);
    for (int i : patch.cells) at(s.patchOf, i) = static_cast<int>(s.patches.size());
    s.patches.push_back(std::move(patch));
  }
}

// Each patch's boundary cells, and whether the object ends there (another cluster, no cell,
// or a depth jump) rather than another patch of the same object.
void findBoundaries(const Grid& g, SceneSegmentation& s) {
  for (std::size_t id = 0; id < s.patches.size(); ++id) {
    SurfacePatch& patch = s.patches[id];
    for (int i : patch.cells) {
      bool onBoundary = false, objectEnds = false;
      for (const auto& d : kFour) {
        const int j = g.neighbour(i, d);
        if (j >= 0 && at(s.patchOf, j) == static_cast<int>(id)) continue;
        onBoundary = true;
        if (j < 0 || at(s.clusterOf, j) != patch.cluster || !g.close(i, j)) objectEnds = true;
      }
      if (!onBoundary) continue;
      patch.boundary.push_back(i);
      patch.edge.push_back(objectEnds);
    }
  }
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
  const Grid g(s.cloud, options);
  std::vector<char> object = objectCandidates(g, s.table, options);
  dropFarUntextured(g, options.untexturedReach, object);
  DisjointSets pieces = linkNeighbours(g, object);
  const std::vector<int> pieceOf = objectPieces(g, s.table, options, object, pieces);
  const std::vector<double> curvature = estimateNormals(g, options, pieceOf, s.normals);
  Patches patches = growPatches(g, options, pieceOf, s.normals, curvature);
  const std::vector<RegionPlane> planes = regionPlanes(s.cloud, patches.regions);
  const std::vector<int> regionOf = spreadRegions(g, pieceOf, patches.patchOf);
  const Meetings meetings = regionMeetings(g, regionOf, planes);
  DisjointSets objects =
      joinConvexMeetings(static_cast<int>(patches.regions.size()), meetings, options);
  rejoinSmallParts(g, options, pieceOf, regionOf, patches, meetings, objects);
  collectClusters(g, options, regionOf, objects, s);
  collectPatches(g, planes, patches, s);
  findBoundaries(g, s);
  return s;
}

}  // namespace visgrab::vision
