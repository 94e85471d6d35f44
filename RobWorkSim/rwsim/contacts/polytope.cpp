#include "rwsim/contacts/polytope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

namespace rwsim::contacts::detail {
namespace {

using rw::geometry::Aabb;
using rw::geometry::TriMesh;
using rw::math::Vector3D;
using Index = std::int32_t;

/// Polytopes with more faces (or edges) than this get a box tree over them.
constexpr std::size_t kTreeThreshold = 64;
/// Polytopes with more vertices than this find supports by hill climbing.
constexpr std::size_t kClimbThreshold = 16;
/// Faces with at least this many vertices get chords in the vertex graph.
constexpr Index kChordFaceSize = 16;
/// Features per tree leaf.
constexpr Index kLeafSize = 4;
/// Neighbouring triangles whose unit normals differ by less than this (about 1.4e-4 rad)
/// and whose vertices lie within the distance tolerance of the seed plane share a face.
constexpr double kCoplanarDot = 1.0 - 1e-8;
/// Distance tolerance for coplanarity, relative to the mesh's bounding-box diagonal.
constexpr double kCoplanarRelDistance = 1e-6;
/// Triangles whose doubled area is below this fraction of their longest squared edge are
/// dropped as degenerate.
constexpr double kDegenerateRatio = 1e-10;

Vector3D unitOrZero(const Vector3D& v) {
  const double n = v.norm();
  return n > 0.0 ? Vector3D(v / n) : Vector3D(Vector3D::Zero());
}

template <class Points>
Aabb boxOf(const Points& points) {
  Aabb box;
  for (const Vector3D& p : points) box.extend(p);
  return box;
}

/// A welded, degenerate-free triangle list with half-edge lookup.
struct CleanMesh {
  std::vector<Vector3D> points;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Vector3D> normals;                       // unit
  std::vector<Vector3D> areaNormals;                   // cross products (twice the area)
  std::map<std::pair<Index, Index>, Index> halfEdges;  // directed edge -> triangle
  double diagonal = 0.0;
};

std::optional<CleanMesh> cleanMesh(const TriMesh& mesh) {
  CleanMesh out;
  std::map<std::array<double, 3>, Index> welded;
  std::vector<Index> remap(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vector3D& v = mesh.vertices[i];
    const auto [it, added] =
        welded.try_emplace({v.x(), v.y(), v.z()}, static_cast<Index>(out.points.size()));
    if (added) out.points.push_back(v);
    remap[i] = it->second;
  }
  Aabb box;
  for (const Vector3D& p : out.points) box.extend(p);
  out.diagonal = box.empty() ? 0.0 : (box.max - box.min).norm();
  for (const auto& t : mesh.triangles) {
    const std::array<Index, 3> w{remap[t[0]], remap[t[1]], remap[t[2]]};
    const Vector3D& a = out.points[static_cast<std::size_t>(w[0])];
    const Vector3D& b = out.points[static_cast<std::size_t>(w[1])];
    const Vector3D& c = out.points[static_cast<std::size_t>(w[2])];
    const Vector3D cross = (b - a).cross(c - a);
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
    if (!(cross.norm() > kDegenerateRatio * longest)) continue;
    const auto index = static_cast<Index>(out.triangles.size());
    for (int k = 0; k < 3; ++k) {
      if (!out.halfEdges.try_emplace({w[k], w[(k + 1) % 3]}, index).second) return std::nullopt;
    }
    out.triangles.push_back(w);
    out.areaNormals.push_back(cross);
    out.normals.push_back(cross.normalized());
  }
  if (out.triangles.empty()) return std::nullopt;
  return out;
}

/// Groups neighbouring coplanar triangles; returns each triangle's group or nullopt for an
/// open mesh.
std::optional<std::vector<Index>> coplanarGroups(const CleanMesh& m, Index& groupCount) {
  const double distanceTolerance = kCoplanarRelDistance * m.diagonal + 1e-15;
  std::vector<Index> group(m.triangles.size(), -1);
  std::vector<Index> queue;
  groupCount = 0;
  for (std::size_t seed = 0; seed < m.triangles.size(); ++seed) {
    if (group[seed] >= 0) continue;
    const Vector3D& n = m.normals[seed];
    const double d = n.dot(m.points[static_cast<std::size_t>(m.triangles[seed][0])]);
    group[seed] = groupCount;
    queue.assign(1, static_cast<Index>(seed));
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const auto& t = m.triangles[static_cast<std::size_t>(queue[q])];
      for (int k = 0; k < 3; ++k) {
        const auto twin = m.halfEdges.find({t[(k + 1) % 3], t[k]});
        if (twin == m.halfEdges.end()) return std::nullopt;
        const auto other = static_cast<std::size_t>(twin->second);
        if (group[other] >= 0 || m.normals[other].dot(n) < kCoplanarDot) continue;
        const auto& o = m.triangles[other];
        bool planar = true;
        for (const Index v : o) {
          planar = planar &&
                   std::abs(n.dot(m.points[static_cast<std::size_t>(v)]) - d) <= distanceTolerance;
        }
        if (!planar) continue;
        group[other] = groupCount;
        queue.push_back(static_cast<Index>(other));
      }
    }
    ++groupCount;
  }
  return group;
}

/// The boundary loop of each group (old vertex indices), or nullopt if a group's boundary is
/// not one simple loop.
std::optional<std::vector<std::vector<Index>>> groupLoops(const CleanMesh& m,
                                                          const std::vector<Index>& group,
                                                          Index groupCount) {
  std::vector<std::map<Index, Index>> next(static_cast<std::size_t>(groupCount));
  std::vector<Index> start(static_cast<std::size_t>(groupCount), -1);
  std::vector<std::size_t> boundaryCount(static_cast<std::size_t>(groupCount), 0);
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto g = static_cast<std::size_t>(group[i]);
    const auto& t = m.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const auto twin = m.halfEdges.at({t[(k + 1) % 3], t[k]});
      if (group[static_cast<std::size_t>(twin)] == group[i]) continue;
      if (!next[g].try_emplace(t[k], t[(k + 1) % 3]).second) return std::nullopt;
      if (start[g] < 0) start[g] = t[k];
      ++boundaryCount[g];
    }
  }
  std::vector<std::vector<Index>> loops(static_cast<std::size_t>(groupCount));
  for (std::size_t g = 0; g < loops.size(); ++g) {
    Index v = start[g];
    while (v >= 0 && loops[g].size() <= boundaryCount[g]) {
      loops[g].push_back(v);
      const auto it = next[g].find(v);
      v = it == next[g].end() ? -1 : it->second;
      if (v == start[g]) break;
    }
    if (v != start[g] || loops[g].size() != boundaryCount[g] || loops[g].size() < 3) {
      return std::nullopt;
    }
  }
  return loops;
}

}  // namespace

QueryBox::QueryBox(const Obb& box, double grow)
    : box_(box),
      absAxes_(box.axes.cwiseAbs()),
      extent_(absAxes_ * box.halfExtents + Vector3D::Constant(grow)),
      grown_(box.halfExtents + Vector3D::Constant(grow)),
      grow_(grow) {}

bool QueryBox::overlaps(const Vector3D& min, const Vector3D& max) const {
  const Vector3D c = 0.5 * (min + max);
  const Vector3D e = 0.5 * (max - min);
  const Vector3D t = box_.center - c;
  if ((t.cwiseAbs() - e - extent_).maxCoeff() > 0.0) return false;
  const Vector3D tLocal = box_.axes.transpose() * t;
  const Vector3D eLocal = absAxes_.transpose() * e;
  return (tLocal.cwiseAbs() - eLocal - grown_).maxCoeff() <= 0.0;
}

bool QueryBox::nearPlane(const Vector3D& n, double offset) const {
  const double reach = (box_.axes.transpose() * n).cwiseAbs().dot(box_.halfExtents);
  return std::abs(n.dot(box_.center) - offset) <= reach + grow_;
}

void FeatureTree::build(std::span<const Aabb> boxes) {
  nodes_.clear();
  order_.resize(boxes.size());
  std::iota(order_.begin(), order_.end(), 0);
  if (!boxes.empty()) buildNode(boxes, 0, static_cast<Index>(boxes.size()));
}

Index FeatureTree::buildNode(std::span<const Aabb> boxes, Index begin, Index end) {
  const auto self = static_cast<Index>(nodes_.size());
  nodes_.emplace_back();
  Aabb box;
  Aabb centers;
  for (Index k = begin; k < end; ++k) {
    const Aabb& b = boxes[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])];
    box.extend(b.min);
    box.extend(b.max);
    centers.extend(0.5 * (b.min + b.max));
  }
  nodes_[static_cast<std::size_t>(self)].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[static_cast<std::size_t>(self)].first = begin;
    nodes_[static_cast<std::size_t>(self)].count = end - begin;
    return self;
  }
  int axis = 0;
  (centers.max - centers.min).maxCoeff(&axis);
  const Index middle = begin + (end - begin) / 2;
  const auto centre = [&](Index i) {
    const Aabb& b = boxes[static_cast<std::size_t>(i)];
    return b.min[axis] + b.max[axis];
  };
  std::nth_element(
      order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
      [&](Index a, Index b) { return centre(a) < centre(b) || (centre(a) == centre(b) && a < b); });
  buildNode(boxes, begin, middle);
  const Index second = buildNode(boxes, middle, end);
  nodes_[static_cast<std::size_t>(self)].second = second;
  return self;
}

void FeatureTree::query(const QueryBox& query, std::vector<Index>& out) const {
  if (nodes_.empty()) return;
  std::array<Index, 64> stack{};
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Index index = stack[--top];
    const Node& node = nodes_[static_cast<std::size_t>(index)];
    if (!query.overlaps(node.box.min, node.box.max)) continue;
    if (node.count > 0) {
      for (Index k = node.first; k < node.first + node.count; ++k) {
        out.push_back(order_[static_cast<std::size_t>(k)]);
      }
      continue;
    }
    stack[top++] = node.second;
    stack[top++] = index + 1;
  }
}

Index supportVertex(const PolytopeView& p, const Vector3D& d, Index& hint) {
  const auto& v = p.vertices;
  if (p.adjacencyOffsets.empty()) {
    Index best = 0;
    double bestDot = v[0].dot(d);
    for (std::size_t i = 1; i < v.size(); ++i) {
      const double dot = v[i].dot(d);
      if (dot > bestDot) {
        bestDot = dot;
        best = static_cast<Index>(i);
      }
    }
    hint = best;
    return best;
  }
  Index current = hint;
  if (current < 0 || static_cast<std::size_t>(current) >= v.size()) {
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    const auto side = static_cast<std::size_t>(axis) * 2 + (d[axis] < 0.0 ? 1 : 0);
    current = p.anchors[side];
  }
  double currentDot = v[static_cast<std::size_t>(current)].dot(d);
  for (bool moved = true; moved;) {
    moved = false;
    const auto node = static_cast<std::size_t>(current);
    for (Index k = p.adjacencyOffsets[node]; k < p.adjacencyOffsets[node + 1]; ++k) {
      const Index n = p.adjacency[static_cast<std::size_t>(k)];
      const double dot = v[static_cast<std::size_t>(n)].dot(d);
      if (dot > currentDot) {
        currentDot = dot;
        current = n;
        moved = true;
      }
    }
  }
  hint = current;
  return current;
}

Index mostAlignedFace(const PolytopeView& p, const Vector3D& d, Index nearVertex) {
  Index best = -1;
  double bestDot = -2.0;
  const auto consider = [&](Index f) {
    const double dot = p.faces[static_cast<std::size_t>(f)].normal.dot(d);
    if (dot > bestDot) {
      bestDot = dot;
      best = f;
    }
  };
  if (p.vertexFaceOffsets.empty() || nearVertex < 0) {
    for (std::size_t f = 0; f < p.faces.size(); ++f) consider(static_cast<Index>(f));
    return best;
  }
  const auto node = static_cast<std::size_t>(nearVertex);
  for (Index k = p.vertexFaceOffsets[node]; k < p.vertexFaceOffsets[node + 1]; ++k) {
    consider(p.vertexFaces[static_cast<std::size_t>(k)]);
  }
  return best;
}

std::optional<Polytope> Polytope::fromConvexMesh(const TriMesh& mesh) {
  const std::optional<CleanMesh> m = cleanMesh(mesh);
  if (!m) return std::nullopt;
  Index groupCount = 0;
  const auto group = coplanarGroups(*m, groupCount);
  if (!group) return std::nullopt;
  const auto loops = groupLoops(*m, *group, groupCount);
  if (!loops) return std::nullopt;

  Polytope p;
  std::vector<Index> newIndex(m->points.size(), -1);
  for (const auto& loop : *loops) {
    for (const Index v : loop) newIndex[static_cast<std::size_t>(v)] = 0;
  }
  for (std::size_t v = 0; v < m->points.size(); ++v) {
    if (newIndex[v] < 0) continue;
    newIndex[v] = static_cast<Index>(p.vertices_.size());
    p.vertices_.push_back(m->points[v]);
  }
  std::vector<Vector3D> groupNormal(loops->size(), Vector3D::Zero());
  for (std::size_t t = 0; t < m->triangles.size(); ++t) {
    groupNormal[static_cast<std::size_t>((*group)[t])] += m->areaNormals[t];
  }
  std::map<std::pair<Index, Index>, Index> edgeFace;  // directed boundary edge -> face
  for (std::size_t g = 0; g < loops->size(); ++g) {
    Face face;
    face.normal = groupNormal[g].normalized();
    face.first = static_cast<Index>(p.faceVertices_.size());
    face.count = static_cast<Index>((*loops)[g].size());
    face.offset = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < (*loops)[g].size(); ++k) {
      const Index v = (*loops)[g][k];
      const Index w = (*loops)[g][(k + 1) % (*loops)[g].size()];
      p.faceVertices_.push_back(newIndex[static_cast<std::size_t>(v)]);
      face.offset = std::max(face.offset, face.normal.dot(m->points[static_cast<std::size_t>(v)]));
      edgeFace[{newIndex[static_cast<std::size_t>(v)], newIndex[static_cast<std::size_t>(w)]}] =
          static_cast<Index>(g);
    }
    p.faces_.push_back(face);
  }
  for (const auto& [key, face] : edgeFace) {
    if (key.first > key.second) continue;
    const auto twin = edgeFace.find({key.second, key.first});
    if (twin == edgeFace.end()) return std::nullopt;
    Edge e;
    e.v0 = key.first;
    e.v1 = key.second;
    e.na = p.faces_[static_cast<std::size_t>(face)].normal;
    e.nb = p.faces_[static_cast<std::size_t>(twin->second)].normal;
    p.edges_.push_back(e);
  }
  p.finish();
  return p;
}

Polytope Polytope::flatPolygon(std::vector<Vector3D> loop, const Vector3D& normal) {
  Polytope p;
  p.flat_ = true;
  p.vertices_ = std::move(loop);
  const auto n = static_cast<Index>(p.vertices_.size());
  Face front;
  front.normal = normal.normalized();
  front.offset = front.normal.dot(p.vertices_[0]);
  front.first = 0;
  front.count = n;
  Face back = front;
  back.normal = -front.normal;
  back.offset = -front.offset;
  back.first = n;
  for (Index k = 0; k < n; ++k) p.faceVertices_.push_back(k);
  for (Index k = 0; k < n; ++k) p.faceVertices_.push_back((n - k) % n);
  p.faces_ = {front, back};
  for (Index k = 0; k < n; ++k) {
    const Index k1 = (k + 1) % n;
    const Vector3D& a = p.vertices_[static_cast<std::size_t>(k)];
    const Vector3D& b = p.vertices_[static_cast<std::size_t>(k1)];
    const Vector3D out = unitOrZero((b - a).cross(front.normal));
    Face side;
    side.normal = out;
    side.offset = out.dot(a);
    side.first = static_cast<Index>(p.faceVertices_.size());
    side.count = 2;
    p.faceVertices_.push_back(k);
    p.faceVertices_.push_back(k1);
    p.faces_.push_back(side);
    Edge e;
    e.v0 = k;
    e.v1 = k1;
    e.na = front.normal;
    e.nb = out;
    p.edges_.push_back(e);
    e.na = out;
    e.nb = back.normal;
    p.edges_.push_back(e);
  }
  p.finish();
  return p;
}

void Polytope::finish() {
  bounds_ = boxOf(vertices_);
  obb_ = rw::proximity::fitObb(vertices_);
  for (Face& f : faces_) {
    f.box = Aabb{};
    for (Index k = 0; k < f.count; ++k) {
      f.box.extend(vertices_[static_cast<std::size_t>(faceVertices_[f.first + k])]);
    }
  }
  for (Edge& e : edges_) {
    e.box = Aabb{};
    e.box.extend(vertices_[static_cast<std::size_t>(e.v0)]);
    e.box.extend(vertices_[static_cast<std::size_t>(e.v1)]);
  }
  buildGraph();
  for (int axis = 0; axis < 6; ++axis) {
    Vector3D d = Vector3D::Zero();
    d[axis / 2] = axis % 2 == 0 ? 1.0 : -1.0;
    Index best = 0;
    for (std::size_t v = 1; v < vertices_.size(); ++v) {
      if (vertices_[v].dot(d) > vertices_[static_cast<std::size_t>(best)].dot(d)) {
        best = static_cast<Index>(v);
      }
    }
    anchors_[static_cast<std::size_t>(axis)] = best;
  }
  std::vector<Aabb> boxes;
  if (faces_.size() > kTreeThreshold) {
    for (const Face& f : faces_) boxes.push_back(f.box);
    faceTree_.build(boxes);
  }
  if (edges_.size() > kTreeThreshold) {
    boxes.clear();
    for (const Edge& e : edges_) boxes.push_back(e.box);
    edgeTree_.build(boxes);
  }
}

void Polytope::buildGraph() {
  std::vector<std::vector<Index>> neighbours(vertices_.size());
  std::vector<std::vector<Index>> faceLists(vertices_.size());
  for (const Edge& e : edges_) {
    neighbours[static_cast<std::size_t>(e.v0)].push_back(e.v1);
    neighbours[static_cast<std::size_t>(e.v1)].push_back(e.v0);
  }
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Face& face = faces_[f];
    for (Index k = 0; k < face.count; ++k) {
      const auto v = static_cast<std::size_t>(faceVertices_[face.first + k]);
      faceLists[v].push_back(static_cast<Index>(f));
      // Chords across large faces (a merged cylinder cap) keep hill climbs short: a climb
      // along the rim alone would take up to half its vertex count.
      for (Index step = face.count / 2; face.count >= kChordFaceSize && step >= 2; step /= 2) {
        neighbours[v].push_back(faceVertices_[face.first + (k + step) % face.count]);
        neighbours[v].push_back(faceVertices_[face.first + (k + face.count - step) % face.count]);
      }
    }
  }
  adjacencyOffsets_.assign(1, 0);
  vertexFaceOffsets_.assign(1, 0);
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    std::sort(neighbours[v].begin(), neighbours[v].end());
    neighbours[v].erase(std::unique(neighbours[v].begin(), neighbours[v].end()),
                        neighbours[v].end());
    adjacency_.insert(adjacency_.end(), neighbours[v].begin(), neighbours[v].end());
    adjacencyOffsets_.push_back(static_cast<Index>(adjacency_.size()));
    vertexFaces_.insert(vertexFaces_.end(), faceLists[v].begin(), faceLists[v].end());
    vertexFaceOffsets_.push_back(static_cast<Index>(vertexFaces_.size()));
  }
}

PolytopeView Polytope::view() const {
  PolytopeView v;
  v.vertices = vertices_;
  v.faces = faces_;
  v.faceVertices = faceVertices_;
  v.edges = edges_;
  if (vertices_.size() > kClimbThreshold) {
    v.adjacencyOffsets = adjacencyOffsets_;
    v.adjacency = adjacency_;
    v.vertexFaceOffsets = vertexFaceOffsets_;
    v.vertexFaces = vertexFaces_;
    v.anchors = anchors_;
  }
  v.faceTree = faceTree_.empty() ? nullptr : &faceTree_;
  v.edgeTree = edgeTree_.empty() ? nullptr : &edgeTree_;
  v.bounds = bounds_;
  return v;
}

TrianglePiece::TrianglePiece(const rw::proximity::Triangle& t, const Vector3D& normal)
    : vertices_(t.v) {
  bounds_ = boxOf(vertices_);
  Face& front = faces_[0];
  front.normal = normal;
  front.offset = normal.dot(vertices_[0]);
  front.first = 0;
  front.count = 3;
  front.box = bounds_;
  faces_[1] = front;
  faces_[1].normal = -normal;
  faces_[1].offset = -front.offset;
  faces_[1].first = 3;
  for (int k = 0; k < 3; ++k) {
    const Vector3D& a = vertices_[static_cast<std::size_t>(k)];
    const Vector3D& b = vertices_[static_cast<std::size_t>((k + 1) % 3)];
    Edge e;
    e.v0 = k;
    e.v1 = (k + 1) % 3;
    e.box = Aabb{};
    e.box.extend(a);
    e.box.extend(b);
    const Vector3D out = unitOrZero((b - a).cross(normal));
    const auto kk = static_cast<std::size_t>(k);
    Face& side = faces_[2 + kk];
    side.normal = out;
    side.offset = out.dot(a);
    side.first = 6 + 2 * k;
    side.count = 2;
    side.box = e.box;
    e.na = normal;
    e.nb = out;
    edges_[2 * kk] = e;
    e.na = out;
    e.nb = -normal;
    edges_[2 * kk + 1] = e;
  }
}

PolytopeView TrianglePiece::view() const {
  PolytopeView v;
  v.vertices = vertices_;
  v.faces = faces_;
  v.faceVertices = loops_;
  v.edges = edges_;
  v.bounds = bounds_;
  return v;
}

}  // namespace rwsim::contacts::detail
