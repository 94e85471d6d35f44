#include "visgrab/objects/mesh_object.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "rw/common/diagnostic.hpp"
#include "rw/geometry/mass_properties.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "rw/math/rpy.hpp"
#include "visgrab/objects/convex_decomposition.hpp"
#include "visgrab/objects/convex_hull.hpp"
#include "visgrab/objects/detail/texture_painter.hpp"
#include "visgrab/render/mesh_loader.hpp"

namespace visgrab::objects {

namespace {

using rw::math::Rotation3D;
using rw::math::Transform3D;
using rw::math::Vector3D;
using Edge = std::pair<std::uint32_t, std::uint32_t>;

std::string format(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

[[noreturn]] void fail(const ObjectSpec& spec, int line, const std::string& message) {
  throw rw::common::LoadError({rw::common::Diagnostic{rw::common::Diagnostic::Severity::kError,
                                                      spec.specFile,
                                                      line,
                                                      0,
                                                      "object \"" + spec.name + "\": " + message,
                                                      {}}});
}

// Directed edge -> number of triangles running along it.
std::map<Edge, int> directedEdges(const rw::geometry::TriMesh& mesh) {
  std::map<Edge, int> edges;
  for (const auto& t : mesh.triangles) {
    for (std::size_t i = 0; i < 3; ++i) ++edges[{t[i], t[(i + 1) % 3]}];
  }
  return edges;
}

// The file's coordinates in the mesh frame before the object frame is placed: scaled, turned.
Transform3D fileTransform(const MeshShapeSpec& shape) {
  Transform3D X = Transform3D::Identity();
  X.linear() = rw::math::rpyToRotation(shape.rpyDegrees * (std::numbers::pi / 180.0)) * shape.scale;
  return X;
}

rw::geometry::TriMesh readMesh(const ObjectSpec& spec, const MeshFileSpec& file,
                               const Transform3D& X) {
  std::shared_ptr<const rw::geometry::TriMesh> loaded;
  try {
    loaded = rw::geometry::loadMesh(file.file);
  } catch (const std::exception& e) {
    fail(spec, file.line, "cannot read \"" + file.written + "\": " + e.what());
  }
  rw::geometry::TriMesh mesh = *loaded;
  for (Vector3D& v : mesh.vertices) v = X * v;
  return mesh;
}

std::string describe(const MeshClosure& c) {
  return std::to_string(c.openEdges + c.crowdedEdges + c.flippedEdges) +
         " edges are not shared by exactly two consistently wound triangles (" +
         std::to_string(c.openEdges) + " open, " + std::to_string(c.crowdedEdges) +
         " shared by more than two, " + std::to_string(c.flippedEdges) + " with flipped winding)";
}

// The closed mesh of the object (in the mesh frame), its holes filled when asked.
rw::geometry::TriMesh closedMesh(const ObjectSpec& spec, const Transform3D& X,
                                 std::vector<std::string>& notes) {
  const MeshShapeSpec& shape = *spec.meshShape;
  rw::geometry::TriMesh mesh = readMesh(spec, shape.mesh, X);
  MeshClosure closure = checkClosure(mesh);
  if (!closure.closed() && shape.fillHoles && closure.crowdedEdges == 0 &&
      closure.flippedEdges == 0) {
    const int holes = fillHoles(mesh);
    notes.push_back("mesh " + shape.mesh.written + ": filled " + std::to_string(holes) +
                    " holes bounded by " + std::to_string(closure.openEdges) + " open edges");
    closure = checkClosure(mesh);
  }
  if (!closure.closed()) {
    fail(spec, shape.mesh.line,
         "the mesh \"" + shape.mesh.written + "\" is not closed: " + describe(closure) +
             (shape.fillHoles || closure.openEdges == 0
                  ? std::string("; repair the mesh")
                  : std::string("; repair it, or set fillHoles=\"true\" to close its holes")));
  }
  const double volume = meshVolume(mesh);
  if (!(volume > 0.0)) {
    fail(spec, shape.mesh.line,
         "the mesh \"" + shape.mesh.written + "\" encloses a volume of " + format(volume) +
             " m^3; expected a positive volume (triangles wound counter-clockwise seen from "
             "outside, scale > 0)");
  }
  return mesh;
}

void addPiece(ObjectModel& model, rw::geometry::TriMesh mesh) {
  const std::string file = model.name + "_hull" + std::to_string(model.collision.size()) + ".stl";
  auto triangles = std::make_shared<const rw::geometry::TriMesh>(std::move(mesh));
  model.collision.push_back({rw::geometry::Geometry::mesh(triangles, file),
                             rw::math::Transform3D::Identity(), triangles});
}

void addCollision(const ObjectSpec& spec, const Transform3D& X, const rw::geometry::TriMesh& mesh,
                  ObjectModel& model) {
  const MeshShapeSpec& shape = *spec.meshShape;
  if (shape.collisionPieces.empty()) {
    DecompositionOptions options;
    options.maxPieces = shape.maxPieces;
    options.concavity = shape.concavity;
    ConvexDecomposition d = decomposeConvex(mesh, options);
    model.notes.push_back(
        "automatic convex decomposition: " + std::to_string(d.pieces.size()) +
        " pieces, their volume " + format(100.0 * (d.piecesVolume / d.meshVolume - 1.0)) +
        " % above the mesh's" +
        (d.flatPartsDropped > 0
             ? ", " + std::to_string(d.flatPartsDropped) + " flat slivers left out"
             : std::string()));
    for (auto& piece : d.pieces) addPiece(model, std::move(piece));
    return;
  }
  for (const MeshFileSpec& file : shape.collisionPieces) {
    const rw::geometry::TriMesh piece = readMesh(spec, file, X);
    rw::geometry::TriMesh hull;
    try {
      hull = convexHull(piece.vertices);
    } catch (const std::exception& e) {
      fail(spec, file.line, "the collision piece \"" + file.written + "\" has no volume");
    }
    const double hullVolume = meshVolume(hull);
    const double volume = meshVolume(piece);
    const bool convex = checkClosure(piece).closed() && volume >= (1.0 - 1e-3) * hullVolume;
    model.notes.push_back(
        "collision piece " + file.written +
        (convex ? ": convex"
                : ": not convex (or not closed), replaced by its convex hull (hull volume " +
                      format(hullVolume) + " m^3, the piece's own " + format(volume) + " m^3)"));
    addPiece(model, std::move(hull));
  }
}

// A cylindrical projection about z: u = angle / 2 pi, v = 0 at the top.
void wrapTexture(const ObjectSpec& spec, std::vector<visual::VisualMesh>& meshes) {
  visual::VisualMesh body;
  float radius = 0.0f;
  float top = 0.0f;
  for (const auto& m : meshes) {
    for (const auto& p : m.positions) {
      radius = std::max(radius, std::hypot(p.x(), p.y()));
      top = std::max(top, p.z());
    }
  }
  for (const auto& m : meshes) {
    for (const auto& t : m.triangles) {
      const auto base = static_cast<std::uint32_t>(body.positions.size());
      std::array<float, 3> u{};
      for (std::size_t i = 0; i < 3; ++i) {
        const Eigen::Vector3f& p = m.positions[t[i]];
        body.positions.push_back(p);
        body.normals.push_back(m.normals[t[i]]);
        u[i] = static_cast<float>(std::atan2(p.y(), p.x()) / (2.0 * std::numbers::pi) + 0.5);
      }
      // A triangle across the seam: its small u values continue past 1 (the texture repeats).
      const float span =
          *std::max_element(u.begin(), u.end()) - *std::min_element(u.begin(), u.end());
      for (std::size_t i = 0; i < 3; ++i) {
        if (span > 0.5f && u[i] < 0.5f) u[i] += 1.0f;
        const float z = body.positions[base + i].z();
        body.uvs.emplace_back(u[i], top > 0.0f ? 1.0f - z / top : 0.0f);
      }
      body.triangles.push_back({base, base + 1, base + 2});
    }
  }
  const AppearanceSpec& a = spec.appearance;
  auto texels = [](double metres) {
    return std::clamp(static_cast<int>(std::ceil(metres * detail::kObjectTexelsPerMetre)), 8, 4096);
  };
  const Eigen::Vector3f ground = detail::linearToSrgb(a.body);
  detail::Canvas canvas(texels(2.0 * std::numbers::pi * radius), texels(top), ground);
  detail::Random random(0x0B1EC7ULL * 1000003ULL + a.seed);
  const detail::PixelRect all{0, 0, canvas.width(), canvas.height()};
  if (a.pattern == PatternKind::kPlainPlastic) {
    detail::paintMaterial(canvas, all, detail::kObjectTexelsPerMetre, a.bodyMaterial, ground, false,
                          random);
    body.specular = detail::materialSpecular(a.bodyMaterial);
  } else {
    std::vector<Eigen::Vector3f> palette;
    for (const auto& c : a.palette) palette.push_back(detail::linearToSrgb(c));
    detail::paintPrinted(canvas, all, detail::kObjectTexelsPerMetre, palette.at(0), palette,
                         random);
    body.specular = a.specular;
  }
  body.colour = Eigen::Vector3f::Ones();
  body.texture = std::make_shared<const visual::RgbImage>(canvas.toImage());
  meshes = {std::move(body)};
}

void addVisual(const ObjectSpec& spec, const Transform3D& X_OF, ObjectModel& model) {
  const MeshShapeSpec& shape = *spec.meshShape;
  std::vector<visual::VisualMesh> meshes;
  try {
    meshes = render::loadVisualMeshes(shape.mesh.file);
  } catch (const std::exception& e) {
    fail(spec, shape.mesh.line, "cannot read \"" + shape.mesh.written + "\": " + e.what());
  }
  const Eigen::Matrix3f R = X_OF.linear().cast<float>() / static_cast<float>(shape.scale);
  const Eigen::Matrix4f X = X_OF.matrix().cast<float>();
  bool textured = false;
  for (auto& m : meshes) {
    for (auto& p : m.positions) p = (X * p.homogeneous()).head<3>();
    for (auto& n : m.normals) n = (R * n).normalized();
    textured = textured || (m.texture && !m.texture->empty());
  }
  if (!textured && spec.hasAppearance) wrapTexture(spec, meshes);
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    model.visual.push_back(
        {meshes.size() == 1 ? std::string("body") : "part" + std::to_string(i), meshes[i]});
  }
}

}  // namespace

MeshClosure checkClosure(const rw::geometry::TriMesh& mesh) {
  MeshClosure c;
  const auto edges = directedEdges(mesh);
  for (const auto& [edge, count] : edges) {
    const auto reverse = edges.find({edge.second, edge.first});
    const int back = reverse == edges.end() ? 0 : reverse->second;
    if (edge.first > edge.second && back > 0) continue;  // counted from the other direction
    const int total = count + back;
    if (total == 1) {
      ++c.openEdges;
    } else if (total > 2) {
      ++c.crowdedEdges;
    } else if (count == 2 || back == 2) {
      ++c.flippedEdges;
    }
  }
  return c;
}

int fillHoles(rw::geometry::TriMesh& mesh) {
  const auto edges = directedEdges(mesh);
  // The holes' loops run against the open edges.
  std::multimap<std::uint32_t, std::uint32_t> next;
  for (const auto& [edge, count] : edges) {
    if (edges.count({edge.second, edge.first}) == 0) next.emplace(edge.second, edge.first);
  }
  int loops = 0;
  while (!next.empty()) {
    // Walk along the boundary; whenever the walk meets itself, the part since then is a loop
    // (a vertex where two holes touch is thus split into two loops, not one figure eight).
    std::vector<std::uint32_t> path{next.begin()->first};
    for (auto it = next.find(path.back()); it != next.end(); it = next.find(path.back())) {
      const std::uint32_t to = it->second;
      next.erase(it);
      const auto seen = std::find(path.begin(), path.end(), to);
      if (seen == path.end()) {
        path.push_back(to);
        continue;
      }
      for (auto v = seen + 1; v + 1 < path.end(); ++v) {
        mesh.triangles.push_back({*seen, *v, *(v + 1)});
      }
      ++loops;
      path.erase(seen + 1, path.end());
    }
  }
  return loops;
}

std::vector<RestingPose> hullRestingPoses(const rw::geometry::TriMesh& hull, const Vector3D& cog,
                                          int maxLying) {
  auto pose = [&hull](std::string name, bool lying, const Rotation3D& R) {
    rw::geometry::Aabb box;
    for (const Vector3D& v : hull.vertices) box.extend(R * v);
    RestingPose p;
    p.name = std::move(name);
    p.lying = lying;
    p.X_TO = rw::math::makeTransform(R, Vector3D(-(box.min.x() + box.max.x()) / 2.0,
                                                 -(box.min.y() + box.max.y()) / 2.0, -box.min.z()));
    p.up = R.transpose() * Vector3D::UnitZ();
    return p;
  };
  // Faces: hull triangles grouped by plane.
  struct Face {
    Vector3D normal;
    double offset;
    std::vector<std::size_t> triangles;
    double margin = -1.0;
  };
  std::vector<Face> faces;
  double size = 0.0;
  for (const Vector3D& v : hull.vertices) size = std::max(size, (v - cog).norm());
  for (std::size_t i = 0; i < hull.triangles.size(); ++i) {
    const auto& t = hull.triangles[i];
    const Vector3D& a = hull.vertices[t[0]];
    const Vector3D n = (hull.vertices[t[1]] - a).cross(hull.vertices[t[2]] - a).normalized();
    const double offset = n.dot(a);
    auto it = std::find_if(faces.begin(), faces.end(), [&](const Face& f) {
      return f.normal.dot(n) > 1.0 - 1e-9 && std::abs(f.offset - offset) < 1e-9 * size;
    });
    if (it == faces.end()) {
      faces.push_back({n, offset, {i}});
    } else {
      it->triangles.push_back(i);
    }
  }
  for (Face& f : faces) {
    const Vector3D c = cog - (f.normal.dot(cog) - f.offset) * f.normal;
    std::map<Edge, int> edges;
    bool inside = false;
    for (const std::size_t i : f.triangles) {
      const auto& t = hull.triangles[i];
      bool in = true;
      for (std::size_t k = 0; k < 3; ++k) {
        const Vector3D& p = hull.vertices[t[k]];
        const Vector3D& q = hull.vertices[t[(k + 1) % 3]];
        if ((q - p).cross(c - p).dot(f.normal) < 0.0) in = false;
        ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
      }
      inside = inside || in;
    }
    if (!inside) continue;
    double margin = std::numeric_limits<double>::infinity();
    for (const auto& [e, count] : edges) {
      if (count != 1) continue;
      const Vector3D& p = hull.vertices[e.first];
      const Vector3D d = (hull.vertices[e.second] - p).normalized();
      margin = std::min(margin, ((c - p) - (c - p).dot(d) * d).norm());
    }
    f.margin = margin;
  }
  std::vector<const Face*> stable;
  for (const Face& f : faces) {
    if (f.margin > 0.0) stable.push_back(&f);
  }
  std::stable_sort(stable.begin(), stable.end(),
                   [](const Face* a, const Face* b) { return a->margin > b->margin; });
  std::vector<RestingPose> poses{pose("standing", false, Rotation3D::Identity())};
  for (const bool nearHorizontal : {true, false}) {
    for (const Face* f : stable) {
      if (static_cast<int>(poses.size()) > maxLying) break;
      const bool horizontal = std::abs(f->normal.z()) < 0.5;
      if (horizontal != nearHorizontal || f->normal.z() < -0.9) continue;
      const Rotation3D R =
          Eigen::Quaterniond::FromTwoVectors(f->normal, -Vector3D::UnitZ()).toRotationMatrix();
      poses.push_back(pose("lying-" + std::to_string(poses.size()), true, R));
    }
    if (poses.size() > 1) break;
  }
  if (poses.size() == 1) {
    Rotation3D rx;  // 90 degrees about x
    rx << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    poses.push_back(pose("lying-1", true, rx));
  }
  return poses;
}

ObjectModel generateMeshObject(const ObjectSpec& spec) {
  if (spec.kind != ShapeKind::kMesh || !spec.meshShape) {
    throw std::invalid_argument(spec.name + ": not a mesh object");
  }
  ObjectModel model;
  model.id = spec.id;
  model.name = spec.name;
  const Transform3D X_file = fileTransform(*spec.meshShape);
  rw::geometry::TriMesh mesh = closedMesh(spec, X_file, model.notes);
  const rw::geometry::SolidProperties solid = rw::geometry::meshSolidProperties(mesh);
  const double mass = spec.density ? *spec.density * solid.volume : spec.mass;
  if (!(mass > 0.0) || !(solid.volume > 0.0)) {
    fail(spec, spec.meshShape->mesh.line, "the mesh has no usable volume");
  }
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vector3D& v : mesh.vertices) lowest = std::min(lowest, v.z());
  const Vector3D shift(-solid.centroid.x(), -solid.centroid.y(), -lowest);
  for (Vector3D& v : mesh.vertices) v += shift;
  Transform3D X_OF = X_file;  // file coordinates -> object frame
  X_OF.pretranslate(shift);
  model.X_O_mesh.linear() =
      rw::math::rpyToRotation(spec.meshShape->rpyDegrees * (std::numbers::pi / 180.0));
  model.X_O_mesh.translation() = shift;
  model.mass.mass = mass;
  model.mass.cog = solid.centroid + shift;
  model.mass.inertia = solid.inertia * (mass / solid.volume);
  model.mass.fromGeometry = true;
  addCollision(spec, X_OF, mesh, model);
  addVisual(spec, X_OF, model);
  std::vector<Vector3D> points;
  for (const auto& piece : model.collision) {
    points.insert(points.end(), piece.triangles->vertices.begin(), piece.triangles->vertices.end());
  }
  model.restingPoses = hullRestingPoses(convexHull(points), model.mass.cog);
  return model;
}

}  // namespace visgrab::objects
