#include "visgrab/objects/detail/mesh_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace visgrab::objects::detail {

namespace {

using rw::geometry::TriMesh;
using visual::VisualMesh;

constexpr int kRoundSteps = 3;           // steps over each face's half of a rounded edge
constexpr double kMaxFlatStep = 0.03;    // longest grid step on a flat box face, m
constexpr double kSmoothBendDeg = 35.0;  // profile bends below this are shaded smoothly

// Unit direction of ring vertex k of n (k = n repeats k = 0 exactly).
Eigen::Vector2d ringDirection(int k, int n) {
  if (k % n == 0) return {1.0, 0.0};
  const double phi = 2.0 * std::numbers::pi * k / n;
  return {std::cos(phi), std::sin(phi)};
}

Eigen::Vector3f toFloat(const Eigen::Vector3d& v) { return v.cast<float>(); }

std::uint32_t index(std::size_t i) { return static_cast<std::uint32_t>(i); }

// Turns every triangle of a convex piece to face away from `inside`.
void orientOutward(TriMesh& mesh, const Eigen::Vector3d& inside) {
  for (auto& t : mesh.triangles) {
    const auto& a = mesh.vertices[t[0]];
    const auto& b = mesh.vertices[t[1]];
    const auto& c = mesh.vertices[t[2]];
    if ((b - a).cross(c - a).dot(a - inside) < 0.0) std::swap(t[1], t[2]);
  }
}

// Grid coordinates along one box axis of half-extent h with edges rounded by r.
std::vector<double> axisSamples(double h, double r) {
  const double inner = h - r;
  const int flat = std::max(1, static_cast<int>(std::ceil(2.0 * inner / kMaxFlatStep)));
  std::vector<double> samples;
  for (int i = 0; i <= flat; ++i) samples.push_back(-inner + 2.0 * inner * i / flat);
  if (r > 0.0) {
    for (int k = 1; k <= kRoundSteps; ++k) {
      const double offset =
          k == kRoundSteps ? r : r * std::tan(std::numbers::pi / 4.0 * k / kRoundSteps);
      samples.push_back(inner + offset);
      samples.insert(samples.begin(), -(inner + offset));
    }
  }
  samples.front() = -h;
  samples.back() = h;
  return samples;
}

// Face-local image coordinates (metres, right and down as seen from outside) of a point p on
// face f of a box of half-extents hh (centred).
Eigen::Vector2d faceCoordinates(int f, const Eigen::Vector3d& p, const Eigen::Vector3d& hh) {
  switch (f) {
    case 0:
      return {p.y() + hh.y(), hh.z() - p.z()};
    case 1:
      return {hh.y() - p.y(), hh.z() - p.z()};
    case 2:
      return {hh.x() - p.x(), hh.z() - p.z()};
    case 3:
      return {p.x() + hh.x(), hh.z() - p.z()};
    case 4:
      return {p.x() + hh.x(), hh.y() - p.y()};
    default:
      return {p.x() + hh.x(), p.y() + hh.y()};
  }
}

double segmentLength(double dz, double dr) { return std::hypot(dz, dr); }

// Outward normal (radial, axial) of the profile segment from point a to point b.
Eigen::Vector2d segmentNormal(const ProfilePoint& a, const ProfilePoint& b) {
  const Eigen::Vector2d n(b.z - a.z, -(b.r - a.r));
  return n.normalized();
}

// The radial/axial normal of the side at height z seen from the segment on side `above`.
Eigen::Vector2d sideNormal(const std::vector<ProfilePoint>& profile, double z, bool above) {
  std::size_t seg = 0;  // segment seg joins points seg and seg + 1
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    if (above ? z >= profile[i].z : z > profile[i].z) seg = i;
  }
  const Eigen::Vector2d own = segmentNormal(profile[seg], profile[seg + 1]);
  const std::size_t joint = above ? seg : seg + 1;  // the profile point z may sit on
  if (profile[joint].z != z || joint == 0 || joint + 1 == profile.size()) return own;
  const Eigen::Vector2d before = segmentNormal(profile[joint - 1], profile[joint]);
  const Eigen::Vector2d after = segmentNormal(profile[joint], profile[joint + 1]);
  const double cosBend = std::clamp(before.dot(after), -1.0, 1.0);
  if (std::acos(cosBend) * 180.0 / std::numbers::pi >= kSmoothBendDeg) return own;
  return (before + after).normalized();
}

double radiusAt(const std::vector<ProfilePoint>& profile, double z) {
  ObjectSpec spec;
  spec.kind = ShapeKind::kLathe;
  spec.profile = profile;
  return spec.radiusAt(z);
}

struct HandleGeometry {
  std::vector<Eigen::Vector3d> points;  // centre line
  std::vector<Eigen::Vector3d> mitres;  // plane normal at each point
  std::vector<Eigen::Vector3d> chords;  // direction of each segment
  double radius = 0.0;
};

HandleGeometry handleGeometry(const ObjectSpec& spec, int segments) {
  HandleGeometry g;
  g.points = handleCentreLine(spec, segments);
  g.radius = spec.handle->thickness / 2.0;
  for (int i = 0; i < segments; ++i) {
    g.chords.push_back((g.points[i + 1] - g.points[i]).normalized());
  }
  g.mitres.push_back(g.chords.front());
  for (int i = 1; i < segments; ++i)
    g.mitres.push_back((g.chords[i - 1] + g.chords[i]).normalized());
  g.mitres.push_back(g.chords.back());
  return g;
}

// Cross-section vertex m of `sides` at joint j, on the prism of segment `seg`.
Eigen::Vector3d sectionVertex(const HandleGeometry& g, int j, int seg, int m, int sides) {
  const Eigen::Vector3d& d = g.chords[seg];
  const Eigen::Vector3d v = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = d.cross(v);
  const Eigen::Vector2d c = ringDirection(m, sides);
  const Eigen::Vector3d o = g.radius * (c.x() * u + c.y() * v);
  const Eigen::Vector3d& n = g.mitres[j];
  const double s = -n.dot(o) / n.dot(d);
  return g.points[j] + o + s * d;
}

}  // namespace

BoxAtlas boxAtlas(const Eigen::Vector3d& size, double texelsPerMetre) {
  constexpr int kPad = 4;
  BoxAtlas atlas;
  atlas.faceSize = {Eigen::Vector2d(size.y(), size.z()), Eigen::Vector2d(size.y(), size.z()),
                    Eigen::Vector2d(size.x(), size.z()), Eigen::Vector2d(size.x(), size.z()),
                    Eigen::Vector2d(size.x(), size.y()), Eigen::Vector2d(size.x(), size.y())};
  // Row 1: the four sides; row 2: top and bottom.
  const std::array<std::array<int, 4>, 2> rows{{{0, 2, 1, 3}, {4, 5, -1, -1}}};
  int top = kPad;
  for (const auto& row : rows) {
    int left = kPad;
    int rowHeight = 0;
    for (int f : row) {
      if (f < 0) continue;
      const int w = static_cast<int>(std::ceil(atlas.faceSize[f].x() * texelsPerMetre));
      const int h = static_cast<int>(std::ceil(atlas.faceSize[f].y() * texelsPerMetre));
      atlas.faces[f] = {left, top, w, h};
      left += w + kPad;
      rowHeight = std::max(rowHeight, h);
    }
    atlas.width = std::max(atlas.width, left);
    top += rowHeight + kPad;
  }
  atlas.height = top;
  return atlas;
}

VisualMesh roundedBoxMesh(const Eigen::Vector3d& size, double radius, const BoxAtlas& atlas) {
  VisualMesh mesh;
  const Eigen::Vector3d hh = size / 2.0;
  const std::array<std::vector<double>, 3> samples{
      axisSamples(hh.x(), radius), axisSamples(hh.y(), radius), axisSamples(hh.z(), radius)};
  const Eigen::Vector3d inner = hh - Eigen::Vector3d::Constant(radius);
  for (int f = 0; f < 6; ++f) {
    const int n = f / 2;
    const double sign = f % 2 == 0 ? 1.0 : -1.0;
    const int ua = (n + 1) % 3;
    const int va = (n + 2) % 3;
    const auto& us = samples[ua];
    const auto& vs = samples[va];
    const auto& rect = atlas.faces[f];
    const std::size_t base = mesh.positions.size();
    for (double vv : vs) {
      for (double uu : us) {
        Eigen::Vector3d p;
        p[n] = sign * hh[n];
        p[ua] = uu;
        p[va] = vv;
        Eigen::Vector3d q = p;
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        normal[n] = sign;
        if (radius > 0.0) {
          const Eigen::Vector3d c = p.cwiseMax(-inner).cwiseMin(inner);
          normal = (p - c).normalized();
          q = c + radius * normal;
        }
        q.z() += hh.z();
        mesh.positions.push_back(toFloat(q));
        mesh.normals.push_back(toFloat(normal));
        const Eigen::Vector2d st = faceCoordinates(f, p, hh);
        const double px = rect[0] + st.x() / atlas.faceSize[f].x() * rect[2];
        const double py = rect[1] + st.y() / atlas.faceSize[f].y() * rect[3];
        mesh.uvs.emplace_back(static_cast<float>(px / atlas.width),
                              static_cast<float>(py / atlas.height));
      }
    }
    const std::size_t nu = us.size();
    for (std::size_t j = 0; j + 1 < vs.size(); ++j) {
      for (std::size_t i = 0; i + 1 < nu; ++i) {
        const auto a = index(base + j * nu + i);
        const auto b = index(base + j * nu + i + 1);
        const auto c = index(base + (j + 1) * nu + i + 1);
        const auto d = index(base + (j + 1) * nu + i);
        if (sign > 0) {
          mesh.triangles.push_back({a, b, c});
          mesh.triangles.push_back({a, c, d});
        } else {
          mesh.triangles.push_back({a, c, b});
          mesh.triangles.push_back({a, d, c});
        }
      }
    }
  }
  return mesh;
}

TriMesh boxPiece(const Eigen::Vector3d& size) {
  TriMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                               i & 4 ? size.z() : 0.0);
  }
  // Two triangles per face, as (corner, edge neighbour, opposite corner, other neighbour).
  const std::array<std::array<std::uint32_t, 4>, 6> faces{
      {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangles.push_back({f[0], f[2], f[3]});
  }
  orientOutward(mesh, Eigen::Vector3d(0.0, 0.0, size.z() / 2.0));
  return mesh;
}

TriMesh frustumPiece(double z0, double r0, double z1, double r1, int sides) {
  TriMesh mesh;
  for (int k = 0; k < sides; ++k) {
    const Eigen::Vector2d c = ringDirection(k, sides);
    mesh.vertices.emplace_back(r0 * c.x(), r0 * c.y(), z0);
  }
  for (int k = 0; k < sides; ++k) {
    const Eigen::Vector2d c = ringDirection(k, sides);
    mesh.vertices.emplace_back(r1 * c.x(), r1 * c.y(), z1);
  }
  const auto bottom = index(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, z0);
  const auto top = index(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, z1);
  const auto n = static_cast<std::uint32_t>(sides);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t k1 = (k + 1) % n;
    mesh.triangles.push_back({k, k1, n + k1});
    mesh.triangles.push_back({k, n + k1, n + k});
    mesh.triangles.push_back({bottom, k1, k});
    mesh.triangles.push_back({top, n + k, n + k1});
  }
  orientOutward(mesh, Eigen::Vector3d(0.0, 0.0, (z0 + z1) / 2.0));
  return mesh;
}

double profileArcLength(const std::vector<ProfilePoint>& profile, double z) {
  double s = 0.0;
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const ProfilePoint& a = profile[i];
    const ProfilePoint& b = profile[i + 1];
    if (z <= a.z) break;
    const double t = z >= b.z ? 1.0 : (z - a.z) / (b.z - a.z);
    s += t * segmentLength(b.z - a.z, b.r - a.r);
  }
  return s;
}

VisualMesh latheSideMesh(const std::vector<ProfilePoint>& profile, double z0, double z1) {
  VisualMesh mesh;
  std::vector<double> zs{z0};
  for (const ProfilePoint& p : profile) {
    if (p.z > z0 && p.z < z1) zs.push_back(p.z);
  }
  zs.push_back(z1);
  const double s0 = profileArcLength(profile, z0);
  const double s1 = profileArcLength(profile, z1);
  const int n = kVisualSides;
  for (std::size_t i = 0; i + 1 < zs.size(); ++i) {
    const std::size_t base = mesh.positions.size();
    for (int end = 0; end < 2; ++end) {
      const double z = zs[i + end];
      const double r = radiusAt(profile, z);
      const Eigen::Vector2d nrz = sideNormal(profile, z, end == 0);
      const float v = static_cast<float>((s1 - profileArcLength(profile, z)) / (s1 - s0));
      for (int k = 0; k <= n; ++k) {
        const Eigen::Vector2d c = ringDirection(k, n);
        mesh.positions.push_back(toFloat(Eigen::Vector3d(r * c.x(), r * c.y(), z)));
        mesh.normals.push_back(
            toFloat(Eigen::Vector3d(nrz.x() * c.x(), nrz.x() * c.y(), nrz.y()).normalized()));
        mesh.uvs.emplace_back(static_cast<float>(k) / n, v);
      }
    }
    const auto row = static_cast<std::uint32_t>(n + 1);
    for (int k = 0; k < n; ++k) {
      const auto a = index(base + k);
      mesh.triangles.push_back({a, a + 1, a + row + 1});
      mesh.triangles.push_back({a, a + row + 1, a + row});
    }
  }
  return mesh;
}

VisualMesh diskMesh(double z, double r, bool up) {
  VisualMesh mesh;
  const Eigen::Vector3f normal(0.0f, 0.0f, up ? 1.0f : -1.0f);
  mesh.positions.push_back(toFloat(Eigen::Vector3d(0.0, 0.0, z)));
  mesh.normals.push_back(normal);
  mesh.uvs.emplace_back(0.5f, 0.5f);
  const int n = kVisualSides;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d c = ringDirection(k, n);
    mesh.positions.push_back(toFloat(Eigen::Vector3d(r * c.x(), r * c.y(), z)));
    mesh.normals.push_back(normal);
    mesh.uvs.emplace_back(static_cast<float>(0.5 + 0.5 * c.x()),
                          static_cast<float>(up ? 0.5 - 0.5 * c.y() : 0.5 + 0.5 * c.y()));
  }
  for (int k = 0; k < n; ++k) {
    const auto a = index(1 + k);
    const auto b = index(1 + (k + 1) % n);
    if (up) {
      mesh.triangles.push_back({0, a, b});
    } else {
      mesh.triangles.push_back({0, b, a});
    }
  }
  return mesh;
}

std::vector<Eigen::Vector3d> handleCentreLine(const ObjectSpec& spec, int segments) {
  const HandleSpec& h = *spec.handle;
  const double low = h.z - h.span / 2.0 - h.thickness / 2.0;
  const double high = h.z + h.span / 2.0 + h.thickness / 2.0;
  const double x0 = spec.minRadiusBetween(low, high) - h.thickness / 2.0;
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k <= segments; ++k) {
    const double theta = -std::numbers::pi / 2.0 + std::numbers::pi * k / segments;
    const double c = 2 * k == segments ? 1.0 : std::cos(theta);
    const double s = 2 * k == segments ? 0.0 : std::sin(theta);
    points.emplace_back(x0 + h.reach * c, 0.0, h.z + h.span / 2.0 * s);
  }
  return points;
}

std::vector<TriMesh> handlePieces(const ObjectSpec& spec) {
  const HandleGeometry g = handleGeometry(spec, kHandleSegments);
  const int m = kHandleCollisionSides;
  std::vector<TriMesh> pieces;
  for (int seg = 0; seg < kHandleSegments; ++seg) {
    TriMesh mesh;
    for (int end = 0; end < 2; ++end) {
      for (int k = 0; k < m; ++k) mesh.vertices.push_back(sectionVertex(g, seg + end, seg, k, m));
    }
    const auto c0 = index(mesh.vertices.size());
    mesh.vertices.push_back(g.points[seg]);
    const auto c1 = index(mesh.vertices.size());
    mesh.vertices.push_back(g.points[seg + 1]);
    const auto n = static_cast<std::uint32_t>(m);
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t k1 = (k + 1) % n;
      mesh.triangles.push_back({k, k1, n + k1});
      mesh.triangles.push_back({k, n + k1, n + k});
      mesh.triangles.push_back({c0, k1, k});
      mesh.triangles.push_back({c1, n + k, n + k1});
    }
    orientOutward(mesh, (g.points[seg] + g.points[seg + 1]) / 2.0);
    pieces.push_back(std::move(mesh));
  }
  return pieces;
}

VisualMesh handleMesh(const ObjectSpec& spec) {
  const int segments = kHandleVisualSegments;
  const HandleGeometry g = handleGeometry(spec, segments);
  const int m = kHandleVisualSides;
  VisualMesh mesh;
  for (int j = 0; j <= segments; ++j) {
    const int seg = std::max(0, j - 1);
    for (int k = 0; k <= m; ++k) {
      const Eigen::Vector3d p = sectionVertex(g, j, seg, k % m, m);
      mesh.positions.push_back(toFloat(p));
      mesh.normals.push_back(toFloat((p - g.points[j]).normalized()));
      mesh.uvs.emplace_back(static_cast<float>(j) / segments, static_cast<float>(k) / m);
    }
  }
  const auto row = static_cast<std::uint32_t>(m + 1);
  std::vector<std::array<std::uint32_t, 3>> tube;
  for (int j = 0; j < segments; ++j) {
    for (int k = 0; k < m; ++k) {
      const auto a = index(j * (m + 1) + k);
      tube.push_back({a, a + 1, a + row + 1});
      tube.push_back({a, a + row + 1, a + row});
    }
  }
  // Wind the tube outwards (the sense depends on the section frame).
  const auto& t = tube.front();
  const Eigen::Vector3f e1 = mesh.positions[t[1]] - mesh.positions[t[0]];
  const Eigen::Vector3f e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
  const bool flip = e1.cross(e2).dot(mesh.normals[t[0]]) < 0.0f;
  for (auto tri : tube) {
    if (flip) std::swap(tri[1], tri[2]);
    mesh.triangles.push_back(tri);
  }
  // End caps: own vertices with flat normals.
  for (int end = 0; end < 2; ++end) {
    const int j = end == 0 ? 0 : segments;
    const Eigen::Vector3d outward = end == 0 ? -g.mitres[0] : g.mitres[segments];
    const auto centre = index(mesh.positions.size());
    mesh.positions.push_back(toFloat(g.points[j]));
    mesh.normals.push_back(toFloat(outward));
    mesh.uvs.emplace_back(static_cast<float>(end), 0.5f);
    for (int k = 0; k < m; ++k) {
      mesh.positions.push_back(mesh.positions[j * (m + 1) + k]);
      mesh.normals.push_back(toFloat(outward));
      mesh.uvs.push_back(mesh.uvs[j * (m + 1) + k]);
    }
    for (int k = 0; k < m; ++k) {
      std::array<std::uint32_t, 3> tri{centre, index(centre + 1 + k),
                                       index(centre + 1 + (k + 1) % m)};
      const Eigen::Vector3f a = mesh.positions[tri[1]] - mesh.positions[tri[0]];
      const Eigen::Vector3f b = mesh.positions[tri[2]] - mesh.positions[tri[0]];
      if (a.cross(b).dot(toFloat(outward)) < 0.0f) std::swap(tri[1], tri[2]);
      mesh.triangles.push_back(tri);
    }
  }
  return mesh;
}

double handleLength(const ObjectSpec& spec) {
  const auto points = handleCentreLine(spec, kHandleVisualSegments);
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) length += (points[i + 1] - points[i]).norm();
  return length;
}

}  // namespace visgrab::objects::detail
