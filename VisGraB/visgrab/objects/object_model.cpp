#include "visgrab/objects/object_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "visgrab/objects/detail/mesh_builder.hpp"
#include "visgrab/objects/detail/texture_painter.hpp"
#include "visgrab/objects/mesh_object.hpp"

namespace visgrab::objects {

namespace {

using detail::Canvas;
using detail::kObjectTexelsPerMetre;
using detail::PixelRect;
using detail::Random;
using rw::math::Rotation3D;
using rw::math::Vector3D;

using detail::materialSpecular;

int texels(double metres) {
  return std::max(8, static_cast<int>(std::ceil(metres * kObjectTexelsPerMetre)));
}

std::vector<Eigen::Vector3f> srgbPalette(const AppearanceSpec& a) {
  std::vector<Eigen::Vector3f> palette;
  for (const auto& c : a.palette) palette.push_back(detail::linearToSrgb(c));
  return palette;
}

std::shared_ptr<const visual::RgbImage> share(visual::RgbImage image) {
  return std::make_shared<const visual::RgbImage>(std::move(image));
}

void validate(const ObjectSpec& spec) {
  const bool box = spec.kind == ShapeKind::kBox;
  if (!(spec.mass > 0.0)) throw std::invalid_argument(spec.name + ": mass must be positive");
  if (box && !(spec.boxSize.minCoeff() > 0.0)) {
    throw std::invalid_argument(spec.name + ": box sizes must be positive");
  }
  if (box && !(spec.cornerRadius >= 0.0 && spec.cornerRadius <= kMaxCornerRadius &&
               spec.cornerRadius <= spec.boxSize.minCoeff() / 4.0)) {
    throw std::invalid_argument(spec.name + ": corner radius out of range");
  }
  if (!box) {
    if (spec.profile.size() < 2 || spec.profile.front().z != 0.0) {
      throw std::invalid_argument(spec.name + ": the profile needs >= 2 points from z = 0");
    }
    for (std::size_t i = 0; i < spec.profile.size(); ++i) {
      if (!(spec.profile[i].r > 0.0) || (i > 0 && !(spec.profile[i].z > spec.profile[i - 1].z))) {
        throw std::invalid_argument(spec.name + ": profile radii must be positive, z increasing");
      }
    }
  }
  if (spec.handle &&
      (box || !(spec.handle->thickness > 0.0) || !(spec.handle->reach > spec.handle->thickness) ||
       !(spec.handle->span > spec.handle->thickness))) {
    throw std::invalid_argument(spec.name + ": invalid handle");
  }
  const bool printed = spec.appearance.pattern != PatternKind::kPlainPlastic;
  if (printed && spec.appearance.palette.size() < 2) {
    throw std::invalid_argument(spec.name + ": the pattern needs two palette colours");
  }
}

// A mesh piece; its name is the STL file object_writer writes for it.
void addMeshPiece(ObjectModel& model, rw::geometry::TriMesh mesh) {
  const std::string file = model.name + "_hull" + std::to_string(model.collision.size()) + ".stl";
  auto triangles = std::make_shared<const rw::geometry::TriMesh>(std::move(mesh));
  model.collision.push_back({rw::geometry::Geometry::mesh(triangles, file),
                             rw::math::Transform3D::Identity(), triangles});
}

// The solid of revolution between two profile points: a cylinder when the radii are equal.
void addRoundPiece(ObjectModel& model, const ProfilePoint& p, const ProfilePoint& q) {
  const double h = q.z - p.z;
  CollisionPiece piece;
  piece.geometry = p.r == q.r ? rw::geometry::Geometry::cylinder(p.r, h)
                              : rw::geometry::Geometry::frustum(p.r, q.r, h);
  piece.X_OG.translation() = Vector3D(0.0, 0.0, (p.z + q.z) / 2.0);
  piece.triangles = std::make_shared<const rw::geometry::TriMesh>(
      detail::frustumPiece(p.z, p.r, q.z, q.r, detail::kCollisionSides));
  model.collision.push_back(std::move(piece));
}

void addBox(const ObjectSpec& spec, Random& random, ObjectModel& model) {
  const AppearanceSpec& a = spec.appearance;
  const auto atlas = detail::boxAtlas(spec.boxSize, kObjectTexelsPerMetre);
  const Eigen::Vector3f ground = detail::linearToSrgb(a.body);
  Canvas canvas(atlas.width, atlas.height, ground);
  const auto palette = srgbPalette(a);
  for (const auto& rect : atlas.faces) {
    Random face(random.next());
    if (a.pattern == PatternKind::kPrintedBox) {
      detail::paintPrinted(canvas, rect, kObjectTexelsPerMetre, ground, palette, face);
    } else {
      detail::paintMaterial(canvas, rect, kObjectTexelsPerMetre, a.bodyMaterial, ground, false,
                            face);
    }
  }
  VisualPart part{"box", detail::roundedBoxMesh(spec.boxSize, spec.cornerRadius, atlas)};
  part.mesh.colour = Eigen::Vector3f::Ones();
  part.mesh.specular =
      a.pattern == PatternKind::kPrintedBox ? a.specular : materialSpecular(a.bodyMaterial);
  part.mesh.texture = share(canvas.toImage());
  if (a.pattern != PatternKind::kPrintedBox) part.material = a.bodyMaterial;
  model.visual.push_back(std::move(part));
  addMeshPiece(model, detail::boxPiece(spec.boxSize));
}

enum class Region { kBody, kLabel, kLid };

Region regionAt(const ObjectSpec& spec, double z) {
  const AppearanceSpec& a = spec.appearance;
  if (a.lidBottom && z > *a.lidBottom) return Region::kLid;
  const bool printed = a.pattern == PatternKind::kLabelBand || a.pattern == PatternKind::kMetalCan;
  if (!printed) return Region::kBody;
  if (!a.label) return Region::kLabel;
  return z > (*a.label)[0] && z < (*a.label)[1] ? Region::kLabel : Region::kBody;
}

void addLathe(const ObjectSpec& spec, Random& random, ObjectModel& model) {
  const AppearanceSpec& a = spec.appearance;
  const double height = spec.height();
  std::vector<double> breaks{0.0, height};
  if (a.label) breaks.insert(breaks.end(), a.label->begin(), a.label->end());
  if (a.lidBottom) breaks.push_back(*a.lidBottom);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  // Runs of one region become one part.
  std::vector<std::pair<double, double>> runs;
  std::vector<Region> regions;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const Region r = regionAt(spec, (breaks[i] + breaks[i + 1]) / 2.0);
    if (!regions.empty() && regions.back() == r) {
      runs.back().second = breaks[i + 1];
    } else {
      runs.emplace_back(breaks[i], breaks[i + 1]);
      regions.push_back(r);
    }
  }
  const auto palette = srgbPalette(a);
  const Eigen::Vector3f body = detail::linearToSrgb(a.body);
  const Eigen::Vector3f lid = detail::linearToSrgb(a.lid);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto [z0, z1] = runs[i];
    double rmax = 0.0;
    for (double z = z0; z < z1; z += (z1 - z0) / 64.0) rmax = std::max(rmax, spec.radiusAt(z));
    rmax = std::max(rmax, spec.radiusAt(z1));
    for (const ProfilePoint& p : spec.profile) {
      if (p.z >= z0 && p.z <= z1) rmax = std::max(rmax, p.r);
    }
    const double length =
        detail::profileArcLength(spec.profile, z1) - detail::profileArcLength(spec.profile, z0);
    Canvas canvas(texels(2.0 * std::numbers::pi * rmax), texels(length), body);
    const PixelRect all{0, 0, canvas.width(), canvas.height()};
    Random part(random.next());
    std::string name = "side" + std::to_string(i);
    float specular = materialSpecular(a.bodyMaterial);
    const bool metalCan = a.pattern == PatternKind::kMetalCan;
    std::optional<SurfaceMaterial> material = metalCan ? SurfaceMaterial::kMetal : a.bodyMaterial;
    if (regions[i] == Region::kLabel) {
      if (!metalCan) material.reset();
      detail::paintPrinted(canvas, all, kObjectTexelsPerMetre, palette[0], palette, part);
      name += "_label";
      specular = a.specular;
    } else if (regions[i] == Region::kLid) {
      detail::paintMaterial(canvas, all, kObjectTexelsPerMetre, a.lidMaterial, lid, false, part);
      name += "_lid";
      specular = materialSpecular(a.lidMaterial);
      material = a.lidMaterial;
    } else {
      detail::paintMaterial(canvas, all, kObjectTexelsPerMetre, a.bodyMaterial, body, false, part);
      name += "_body";
    }
    VisualPart side{name, detail::latheSideMesh(spec.profile, z0, z1)};
    side.mesh.colour = Eigen::Vector3f::Ones();
    side.mesh.specular = specular;
    side.mesh.texture = share(canvas.toImage());
    side.material = material;
    model.visual.push_back(std::move(side));
  }
  const bool metalCan = a.pattern == PatternKind::kMetalCan;
  for (int end = 0; end < 2; ++end) {
    const bool top = end == 1;
    const bool isLid = top && a.lidBottom.has_value();
    const SurfaceMaterial material = isLid ? a.lidMaterial : a.bodyMaterial;
    const ProfilePoint& p = top ? spec.profile.back() : spec.profile.front();
    Canvas canvas(texels(2.0 * p.r), texels(2.0 * p.r), isLid ? lid : body);
    Random part(random.next());
    detail::paintMaterial(canvas, {0, 0, canvas.width(), canvas.height()}, kObjectTexelsPerMetre,
                          material, isLid ? lid : body,
                          material == SurfaceMaterial::kMetal || metalCan, part);
    VisualPart cap{top ? "top" : "bottom", detail::diskMesh(p.z, p.r, top)};
    cap.mesh.colour = Eigen::Vector3f::Ones();
    cap.mesh.specular = materialSpecular(material);
    cap.mesh.texture = share(canvas.toImage());
    cap.material = metalCan && !isLid ? SurfaceMaterial::kMetal : material;
    model.visual.push_back(std::move(cap));
  }
  for (std::size_t i = 0; i + 1 < spec.profile.size(); ++i) {
    const ProfilePoint& p = spec.profile[i];
    const ProfilePoint& q = spec.profile[i + 1];
    addRoundPiece(model, p, q);
  }
  if (spec.handle) {
    const double length = detail::handleLength(spec);
    Canvas canvas(texels(length), texels(std::numbers::pi * spec.handle->thickness), body);
    Random part(random.next());
    detail::paintMaterial(canvas, {0, 0, canvas.width(), canvas.height()}, kObjectTexelsPerMetre,
                          a.bodyMaterial, body, false, part);
    VisualPart handle{"handle", detail::handleMesh(spec)};
    handle.mesh.colour = Eigen::Vector3f::Ones();
    handle.mesh.specular = materialSpecular(a.bodyMaterial);
    handle.mesh.texture = share(canvas.toImage());
    handle.material = a.bodyMaterial;
    model.visual.push_back(std::move(handle));
    for (auto& piece : detail::handlePieces(spec)) {
      addMeshPiece(model, std::move(piece));
    }
  }
}

RestingPose restOn(const ObjectModel& model, std::string name, const Rotation3D& R) {
  rw::geometry::Aabb box;
  for (const auto& piece : model.collision) {
    for (const Vector3D& v : piece.triangles->vertices) box.extend(R * v);
  }
  RestingPose pose;
  pose.name = std::move(name);
  pose.lying = std::abs(R(2, 2)) < 0.5;
  pose.X_TO =
      rw::math::makeTransform(R, Vector3D(-(box.min.x() + box.max.x()) / 2.0,
                                          -(box.min.y() + box.max.y()) / 2.0, -box.min.z()));
  pose.up = R.transpose() * Vector3D::UnitZ();
  return pose;
}

void addRestingPoses(const ObjectSpec& spec, ObjectModel& model) {
  Rotation3D rx;  // 90 degrees about x
  rx << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  Rotation3D ry;  // 90 degrees about y
  ry << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  Rotation3D rz;  // 90 degrees about z
  rz << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  model.restingPoses.push_back(restOn(model, "standing", Rotation3D::Identity()));
  if (spec.kind == ShapeKind::kBox) {
    model.restingPoses.push_back(restOn(model, "lying-x", rx));
    model.restingPoses.push_back(restOn(model, "lying-y", ry));
  } else if (spec.handle) {
    model.restingPoses.push_back(restOn(model, "lying", rx * rz));  // handle up
  } else {
    model.restingPoses.push_back(restOn(model, "lying", rx));
  }
}

}  // namespace

rw::geometry::Aabb ObjectModel::collisionBounds() const {
  rw::geometry::Aabb box;
  for (const auto& piece : collision) {
    for (const Vector3D& v : piece.triangles->vertices) box.extend(v);
  }
  return box;
}

ObjectModel generateObject(const ObjectSpec& spec) {
  if (spec.kind == ShapeKind::kMesh) return generateMeshObject(spec);
  validate(spec);
  ObjectModel model;
  model.id = spec.id;
  model.name = spec.name;
  Random random(0x0B1EC7ULL * 1000003ULL + spec.appearance.seed);
  if (spec.kind == ShapeKind::kBox) {
    addBox(spec, random, model);
  } else {
    addLathe(spec, random, model);
  }
  std::vector<rw::geometry::PlacedGeometry> placed;
  for (const auto& piece : model.collision) placed.push_back({piece.geometry, piece.X_OG});
  model.mass = rw::geometry::estimateMassProperties(spec.mass, placed);
  addRestingPoses(spec, model);
  return model;
}

TableModel generateTable(const TableSpec& spec) {
  if (!(spec.x > 0.0 && spec.y > 0.0)) {
    throw std::invalid_argument("table " + spec.name + ": size must be positive");
  }
  TableModel table;
  table.name = spec.name;
  table.x = spec.x;
  table.y = spec.y;
  constexpr double kStep = 0.1;
  const int nx = std::max(1, static_cast<int>(std::ceil(spec.x / kStep)));
  const int ny = std::max(1, static_cast<int>(std::ceil(spec.y / kStep)));
  visual::VisualMesh& m = table.surface;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double u = static_cast<double>(i) / nx;
      const double v = static_cast<double>(j) / ny;
      m.positions.emplace_back(static_cast<float>((u - 0.5) * spec.x),
                               static_cast<float>((0.5 - v) * spec.y), 0.0f);
      m.normals.emplace_back(0.0f, 0.0f, 1.0f);
      m.uvs.emplace_back(static_cast<float>(u), static_cast<float>(v));
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const auto a = static_cast<std::uint32_t>(j * (nx + 1) + i);
      const auto row = static_cast<std::uint32_t>(nx + 1);
      // Rows run towards -y, so (a, a + row, a + row + 1) winds counter-clockwise from above.
      m.triangles.push_back({a, a + row, a + row + 1});
      m.triangles.push_back({a, a + row + 1, a + 1});
    }
  }
  m.colour = Eigen::Vector3f::Ones();
  m.specular = spec.pattern == TablePattern::kPlain ? 0.15f : 0.05f;
  m.texture = std::make_shared<const visual::RgbImage>(detail::tableTexture(spec));
  return table;
}

}  // namespace visgrab::objects
