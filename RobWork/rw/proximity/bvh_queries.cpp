#include "rw/proximity/bvh_queries.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "rw/proximity/gjk.hpp"
#include "rw/proximity/triangle_queries.hpp"

namespace rw::proximity {

using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;

namespace {

// A LIFO stack that lives on the call stack up to kInline entries and spills to the heap beyond.
template <class T>
class TraversalStack {
 public:
  bool empty() const { return size_ == 0; }
  void push(const T& item) {
    if (size_ < kInline) {
      inline_[size_] = item;
    } else {
      overflow_.push_back(item);
    }
    ++size_;
  }
  T pop() {
    --size_;
    if (size_ < kInline) return inline_[size_];
    T item = overflow_.back();
    overflow_.pop_back();
    return item;
  }

 private:
  static constexpr std::size_t kInline = 128;
  std::array<T, kInline> inline_;
  std::vector<T> overflow_;
  std::size_t size_ = 0;
};

struct NodePair {
  std::int32_t a;
  std::int32_t b;
  double lowerBound;
};

Triangle transformed(const Triangle& t, const Rotation3D& R, const Vector3D& p) {
  return Triangle{{R * t.v[0] + p, R * t.v[1] + p, R * t.v[2] + p}};
}

// Descend into `a` rather than `b`: a is internal and at least as large, or b is a leaf.
bool descendIntoA(const Bvh::Node& a, const Bvh::Node& b) {
  if (a.isLeaf()) return false;
  if (b.isLeaf()) return true;
  return a.box.halfExtents.maxCoeff() >= b.box.halfExtents.maxCoeff();
}

// Pushes both children pairs, nearer one last so it is popped first; skips hopeless ones.
void pushOrdered(TraversalStack<NodePair>& stack, NodePair first, NodePair second, double best) {
  if (first.lowerBound > second.lowerBound) std::swap(first, second);
  if (second.lowerBound < best) stack.push(second);
  if (first.lowerBound < best) stack.push(first);
}

void leafDistance(const Bvh& a, const Bvh::Node& na, const Bvh& b, const Bvh::Node& nb,
                  const Rotation3D& R, const Vector3D& t, DistanceResult& best) {
  for (std::int32_t j = nb.first; j < nb.first + nb.count; ++j) {
    const Triangle tb = transformed(b.triangles()[static_cast<std::size_t>(j)], R, t);
    for (std::int32_t i = na.first; i < na.first + na.count; ++i) {
      const DistanceResult d = triangleDistance(a.triangles()[static_cast<std::size_t>(i)], tb);
      if (d.distance < best.distance) best = d;
    }
  }
}

bool leafCollides(const Bvh& a, const Bvh::Node& na, const Bvh& b, const Bvh::Node& nb,
                  const Rotation3D& R, const Vector3D& t, double tolerance) {
  for (std::int32_t j = nb.first; j < nb.first + nb.count; ++j) {
    const Triangle tb = transformed(b.triangles()[static_cast<std::size_t>(j)], R, t);
    for (std::int32_t i = na.first; i < na.first + na.count; ++i) {
      if (trianglesIntersect(a.triangles()[static_cast<std::size_t>(i)], tb, tolerance)) {
        return true;
      }
    }
  }
  return false;
}

ConvexShape triangleShape(const Triangle& t) { return ConvexShape::hull(t.v); }

}  // namespace

bool bvhCollides(const Bvh& a, const Bvh& b, const Transform3D& X_ab, double tolerance) {
  const Rotation3D R = X_ab.linear();
  const Vector3D t = X_ab.translation();
  TraversalStack<NodePair> stack;
  stack.push({0, 0, 0.0});
  while (!stack.empty()) {
    const NodePair pair = stack.pop();
    const Bvh::Node& na = a.nodes()[static_cast<std::size_t>(pair.a)];
    const Bvh::Node& nb = b.nodes()[static_cast<std::size_t>(pair.b)];
    if (obbDisjoint(na.box, nb.box, R, t, tolerance)) continue;
    if (na.isLeaf() && nb.isLeaf()) {
      if (leafCollides(a, na, b, nb, R, t, tolerance)) return true;
    } else if (descendIntoA(na, nb)) {
      stack.push({na.second, pair.b, 0.0});
      stack.push({pair.a + 1, pair.b, 0.0});
    } else {
      stack.push({pair.a, nb.second, 0.0});
      stack.push({pair.a, pair.b + 1, 0.0});
    }
  }
  return false;
}

DistanceResult bvhDistance(const Bvh& a, const Bvh& b, const Transform3D& X_ab, double upperBound) {
  const Rotation3D R = X_ab.linear();
  const Vector3D t = X_ab.translation();
  const auto bound = [&](std::int32_t i, std::int32_t j) {
    return NodePair{i, j,
                    obbDistanceLowerBound(a.nodes()[static_cast<std::size_t>(i)].box,
                                          b.nodes()[static_cast<std::size_t>(j)].box, R, t)};
  };
  DistanceResult best;
  best.distance = upperBound;
  TraversalStack<NodePair> stack;
  stack.push(bound(0, 0));
  while (!stack.empty() && best.distance > 0.0) {
    const NodePair pair = stack.pop();
    if (pair.lowerBound >= best.distance) continue;
    const Bvh::Node& na = a.nodes()[static_cast<std::size_t>(pair.a)];
    const Bvh::Node& nb = b.nodes()[static_cast<std::size_t>(pair.b)];
    if (na.isLeaf() && nb.isLeaf()) {
      leafDistance(a, na, b, nb, R, t, best);
    } else if (descendIntoA(na, nb)) {
      pushOrdered(stack, bound(pair.a + 1, pair.b), bound(na.second, pair.b), best.distance);
    } else {
      pushOrdered(stack, bound(pair.a, pair.b + 1), bound(pair.a, nb.second), best.distance);
    }
  }
  if (best.distance >= upperBound) best.distance = std::numeric_limits<double>::infinity();
  return best;
}

bool bvhConvexCollides(const Bvh& a, const ConvexShape& b, const Obb& boxB, const Transform3D& X_ab,
                       double tolerance) {
  const Rotation3D R = X_ab.linear();
  const Vector3D t = X_ab.translation();
  TraversalStack<NodePair> stack;
  stack.push({0, 0, 0.0});
  while (!stack.empty()) {
    const NodePair pair = stack.pop();
    const Bvh::Node& na = a.nodes()[static_cast<std::size_t>(pair.a)];
    if (obbDisjoint(na.box, boxB, R, t, tolerance)) continue;
    if (!na.isLeaf()) {
      stack.push({na.second, 0, 0.0});
      stack.push({pair.a + 1, 0, 0.0});
      continue;
    }
    for (std::int32_t i = na.first; i < na.first + na.count; ++i) {
      const ConvexShape tri = triangleShape(a.triangles()[static_cast<std::size_t>(i)]);
      const GjkResult r = gjkDistance(tri, b, X_ab, tolerance, tolerance);
      if (!r.exceeded && r.distance <= tolerance) return true;
    }
  }
  return false;
}

DistanceResult bvhConvexDistance(const Bvh& a, const ConvexShape& b, const Obb& boxB,
                                 const Transform3D& X_ab, double upperBound) {
  const Rotation3D R = X_ab.linear();
  const Vector3D t = X_ab.translation();
  const auto bound = [&](std::int32_t i) {
    return NodePair{i, 0,
                    obbDistanceLowerBound(a.nodes()[static_cast<std::size_t>(i)].box, boxB, R, t)};
  };
  DistanceResult best;
  best.distance = upperBound;
  TraversalStack<NodePair> stack;
  stack.push(bound(0));
  while (!stack.empty() && best.distance > 0.0) {
    const NodePair pair = stack.pop();
    if (pair.lowerBound >= best.distance) continue;
    const Bvh::Node& na = a.nodes()[static_cast<std::size_t>(pair.a)];
    if (!na.isLeaf()) {
      pushOrdered(stack, bound(pair.a + 1), bound(na.second), best.distance);
      continue;
    }
    for (std::int32_t i = na.first; i < na.first + na.count; ++i) {
      const ConvexShape tri = triangleShape(a.triangles()[static_cast<std::size_t>(i)]);
      const GjkResult r = gjkDistance(tri, b, X_ab, 0.0, best.distance);
      if (!r.exceeded && r.distance < best.distance) best = {r.distance, r.pointA, r.pointB};
    }
  }
  if (best.distance >= upperBound) best.distance = std::numeric_limits<double>::infinity();
  return best;
}

LowestPoint bvhLowestPoint(const Bvh& a, const Transform3D& X_pa, double stopAtOrBelow) {
  const Vector3D up = X_pa.linear().row(2).transpose();
  const double offset = X_pa.translation().z();
  const auto bound = [&](std::int32_t i) {
    const Obb& box = a.nodes()[static_cast<std::size_t>(i)].box;
    const double reach = (box.axes.transpose() * up).cwiseAbs().dot(box.halfExtents);
    return NodePair{i, 0, up.dot(box.center) + offset - reach};
  };
  LowestPoint best;
  best.height = std::numeric_limits<double>::infinity();
  TraversalStack<NodePair> stack;
  stack.push(bound(0));
  while (!stack.empty() && best.height > stopAtOrBelow) {
    const NodePair pair = stack.pop();
    if (pair.lowerBound >= best.height) continue;
    const Bvh::Node& na = a.nodes()[static_cast<std::size_t>(pair.a)];
    if (!na.isLeaf()) {
      pushOrdered(stack, bound(pair.a + 1), bound(na.second), best.height);
      continue;
    }
    for (std::int32_t i = na.first; i < na.first + na.count; ++i) {
      for (const Vector3D& v : a.triangles()[static_cast<std::size_t>(i)].v) {
        const double h = up.dot(v) + offset;
        if (h < best.height) best = {h, v};
      }
    }
  }
  best.point = X_pa * best.point;
  return best;
}

}  // namespace rw::proximity
