#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "objects_test_support.hpp"
#include "rw/geometry/mass_properties.hpp"
#include "visgrab/objects/object_model.hpp"

namespace {

using visgrab::objects::ObjectModel;
using visgrab::objects::ObjectSpec;
using visgrab::objects::PatternKind;
using visgrab::objects::ShapeKind;
using namespace visgrab::test::objects;

// Profile radius at z, by linear interpolation (the test's own reading of the spec).
double profileRadius(const ObjectSpec& o, double z) {
  for (std::size_t i = 1; i < o.profile.size(); ++i) {
    if (z <= o.profile[i].z) {
      const auto& a = o.profile[i - 1];
      const auto& b = o.profile[i];
      return a.r + (b.r - a.r) * (z - a.z) / (b.z - a.z);
    }
  }
  return o.profile.back().r;
}

// The bounding box the spec describes: [min, max] corners.
std::pair<Eigen::Vector3d, Eigen::Vector3d> specBounds(const ObjectSpec& o) {
  if (o.kind == ShapeKind::kBox) {
    const Eigen::Vector3d h = o.boxSize / 2.0;
    return {Eigen::Vector3d(-h.x(), -h.y(), 0.0), Eigen::Vector3d(h.x(), h.y(), o.boxSize.z())};
  }
  double rmax = 0.0;
  for (const auto& p : o.profile) rmax = std::max(rmax, p.r);
  double xmax = rmax;
  double ymax = rmax;
  if (o.handle) {
    // The handle stands `reach` out from the narrowest wall over its attachment height.
    const auto& h = *o.handle;
    const double z0 = h.z - h.span / 2 - h.thickness / 2;
    const double z1 = h.z + h.span / 2 + h.thickness / 2;
    double wall = 1e9;
    for (int i = 0; i <= 10000; ++i)
      wall = std::min(wall, profileRadius(o, z0 + (z1 - z0) * i / 10000));
    xmax = std::max(xmax, wall + h.reach);
    ymax = std::max(ymax, h.thickness / 2);
  }
  return {Eigen::Vector3d(-rmax, -ymax, 0.0), Eigen::Vector3d(xmax, ymax, o.profile.back().z)};
}

class EveryObject : public ::testing::TestWithParam<int> {
 protected:
  const ObjectSpec& spec() const { return projectSpec().objects.at(GetParam()); }
  const ObjectModel& model() const { return projectModel(GetParam()); }
};

TEST_P(EveryObject, CollisionBoundsMatchTheSpec) {
  const auto [lo, hi] = specBounds(spec());
  const auto box = model().collisionBounds();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(box.min[i], lo[i], 1e-3) << spec().name << " axis " << i;
    EXPECT_NEAR(box.max[i], hi[i], 1e-3) << spec().name << " axis " << i;
  }
  EXPECT_EQ(model().id, spec().id);
  EXPECT_EQ(model().name, spec().name);
}

TEST_P(EveryObject, CollisionPiecesAreClosedAndConvex) {
  ASSERT_FALSE(model().collision.empty());
  for (std::size_t k = 0; k < model().collision.size(); ++k) {
    const auto& piece = *model().collision[k].triangles;
    const auto triangles = meshTriangles(piece);
    EXPECT_EQ(unmatchedEdges(triangles), 0) << spec().name << " piece " << k;
    EXPECT_GT(signedVolume(triangles), 0.0) << spec().name << " piece " << k;
    double worst = -1.0;
    for (const auto& t : triangles) {
      const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
      for (const auto& v : piece.vertices) worst = std::max(worst, n.dot(v - t[0]));
    }
    EXPECT_LE(worst, 1e-9) << spec().name << " piece " << k << " is not convex";
  }
}

TEST_P(EveryObject, VisualSurfaceIsClosedOutwardWithUnitNormals) {
  const auto triangles = visualTriangles(model());
  EXPECT_EQ(unmatchedEdges(triangles), 0) << spec().name;
  EXPECT_GT(signedVolume(triangles), 0.0) << spec().name;
  for (const auto& part : model().visual) {
    const auto& m = part.mesh;
    ASSERT_EQ(m.normals.size(), m.positions.size()) << part.name;
    ASSERT_EQ(m.uvs.size(), m.positions.size()) << part.name;
    ASSERT_TRUE(m.texture && !m.texture->empty()) << part.name;
    EXPECT_EQ(m.texture->pixels.size(),
              static_cast<std::size_t>(m.texture->width) * m.texture->height * 3);
    for (std::size_t i = 0; i < m.normals.size(); ++i) {
      ASSERT_NEAR(m.normals[i].norm(), 1.0f, 1e-5f) << spec().name << " " << part.name;
      ASSERT_TRUE((m.uvs[i].array() >= 0.0f).all() && (m.uvs[i].array() <= 1.0f).all());
    }
    // Vertex normals agree with the faces around them (smooth shading, outward).
    for (const auto& t : m.triangles) {
      const Eigen::Vector3f n =
          (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
      if (n.norm() < 1e-12f) continue;
      for (auto i : t) {
        EXPECT_GT(n.normalized().dot(m.normals[i]), 0.5f) << spec().name << " " << part.name;
      }
    }
  }
}

TEST_P(EveryObject, VisualSurfaceLiesOnTheCollisionSurface) {
  std::vector<Triangle> collision;
  for (const auto& piece : model().collision) {
    const auto t = meshTriangles(*piece.triangles);
    collision.insert(collision.end(), t.begin(), t.end());
  }
  double worst = 0.0;
  for (const auto& part : model().visual) {
    for (const auto& p : part.mesh.positions) {
      double d = 1e9;
      for (const auto& t : collision) d = std::min(d, pointTriangleDistance(p.cast<double>(), t));
      worst = std::max(worst, d);
    }
  }
  EXPECT_LE(worst, 0.002) << spec().name;
}

TEST_P(EveryObject, MassPropertiesFromUniformDensity) {
  const auto& m = model().mass;
  EXPECT_DOUBLE_EQ(m.mass, spec().mass);
  EXPECT_TRUE(m.fromGeometry);
  EXPECT_TRUE(m.inertia.isApprox(m.inertia.transpose(), 1e-12));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m.inertia);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  // Mirror symmetric in y (handles lie in the xz-plane): COG on y = 0; without a handle also
  // on the z axis; always within the body's height.
  EXPECT_NEAR(m.cog.y(), 0.0, 1e-9) << spec().name;
  if (spec().handle) {
    EXPECT_GT(m.cog.x(), 0.0) << spec().name;
  } else {
    EXPECT_NEAR(m.cog.x(), 0.0, 1e-9) << spec().name;
  }
  EXPECT_GT(m.cog.z(), 0.0);
  EXPECT_LT(m.cog.z(), spec().height());
}

TEST_P(EveryObject, RestingPosesTouchTheTable) {
  const auto& poses = model().restingPoses;
  ASSERT_GE(poses.size(), 2u);
  EXPECT_EQ(poses.front().name, "standing");
  EXPECT_FALSE(poses.front().lying);
  int lying = 0;
  for (const auto& pose : poses) {
    double low = 1e9;
    for (const auto& piece : model().collision) {
      for (const auto& v : piece.triangles->vertices) low = std::min(low, (pose.X_TO * v).z());
    }
    EXPECT_NEAR(low, 0.0, 1e-12) << spec().name << " " << pose.name;
    const Eigen::Vector3d up = pose.X_TO.linear() * pose.up;
    EXPECT_NEAR(up.z(), 1.0, 1e-12);
    if (pose.lying) {
      ++lying;
      // The object's z axis is horizontal.
      EXPECT_NEAR((pose.X_TO.linear() * Eigen::Vector3d::UnitZ()).z(), 0.0, 1e-12);
    }
  }
  EXPECT_GE(lying, 1);
}

TEST_P(EveryObject, PrintedTexturesHaveStereoDetail) {
  // A 7x7 block matcher needs texture well above sensor noise (a few grey levels) nearly
  // everywhere on printed surfaces; plain plastic is allowed to be weaker.
  const auto pattern = spec().appearance.pattern;
  for (const auto& part : model().visual) {
    const bool printed =
        pattern == PatternKind::kPrintedBox || part.name.find("_label") != std::string::npos;
    if (printed) {
      EXPECT_GT(texturedFraction(part.mesh, 6.0), 0.9) << spec().name << " " << part.name;
    } else {
      EXPECT_GT(texturedFraction(part.mesh, 2.0), 0.8) << spec().name << " " << part.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Objects, EveryObject, ::testing::Range(0, 18),
                         [](const auto& p) { return projectSpec().objects.at(p.param).name; });

TEST(ObjectModel, BoxVolumeAndInertiaAreAnalytic) {
  int boxes = 0;
  for (std::size_t i = 0; i < projectSpec().objects.size(); ++i) {
    const auto& o = projectSpec().objects[i];
    if (o.kind != ShapeKind::kBox) continue;
    ++boxes;
    const auto& model = projectModels()[i];
    double volume = 0.0;
    for (const auto& piece : model.collision)
      volume += signedVolume(meshTriangles(*piece.triangles));
    const double a = o.boxSize.x(), b = o.boxSize.y(), c = o.boxSize.z();
    EXPECT_NEAR(volume / (a * b * c), 1.0, 1e-9) << o.name;
    const double m = o.mass;
    const Eigen::Vector3d expected(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                                   m * (a * a + b * b) / 12);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(model.mass.inertia(k, k) / expected[k], 1.0, 1e-6) << o.name << " " << k;
      for (int l = 0; l < 3; ++l) {
        if (l != k) {
          EXPECT_NEAR(model.mass.inertia(k, l), 0.0, 1e-6 * expected.minCoeff());
        }
      }
    }
    EXPECT_NEAR(model.mass.cog.z(), c / 2, 1e-12) << o.name;
  }
  EXPECT_GE(boxes, 5);
}

TEST(ObjectModel, CylinderVolumeAndInertiaMatchTheCylinder) {
  int cylinders = 0;
  for (std::size_t i = 0; i < projectSpec().objects.size(); ++i) {
    const auto& o = projectSpec().objects[i];
    if (o.kind != ShapeKind::kCylinder || o.handle) continue;
    ++cylinders;
    const auto& model = projectModels()[i];
    double volume = 0.0;
    for (const auto& piece : model.collision)
      volume += signedVolume(meshTriangles(*piece.triangles));
    const double r = o.profile[0].r, h = o.profile[1].z;
    // The analytic cylinder within 1%, and exactly the inscribed regular polygon's prism.
    EXPECT_NEAR(volume / (std::numbers::pi * r * r * h), 1.0, 0.01) << o.name;
    constexpr int kSides = 32;  // the documented faceting of cylinder pieces
    const double polygon = 0.5 * kSides * r * r * std::sin(2 * std::numbers::pi / kSides);
    EXPECT_NEAR(volume / (polygon * h), 1.0, 1e-9) << o.name;
    // The mass properties are those of the true cylinder, not of the polygon's prism.
    const double m = o.mass;
    EXPECT_NEAR(model.mass.inertia(2, 2) / (m * r * r / 2), 1.0, 1e-9) << o.name;
    EXPECT_NEAR(model.mass.inertia(0, 0) / (m * (3 * r * r + h * h) / 12), 1.0, 1e-9) << o.name;
    EXPECT_NEAR(model.mass.cog.z(), h / 2, 1e-12);
  }
  EXPECT_GE(cylinders, 1);
}

TEST(ObjectModel, LatheSegmentsAreCylindersAndFrusta) {
  using rw::geometry::GeometryType;
  int lathes = 0;
  for (std::size_t i = 0; i < projectSpec().objects.size(); ++i) {
    const auto& o = projectSpec().objects[i];
    const auto& model = projectModels()[i];
    if (o.kind == ShapeKind::kBox) {
      ASSERT_EQ(model.collision.size(), 1u) << o.name;
      EXPECT_EQ(model.collision[0].geometry->type(), GeometryType::kMesh) << o.name;
      continue;
    }
    ++lathes;
    const std::size_t segments = o.profile.size() - 1;
    ASSERT_GE(model.collision.size(), segments) << o.name;
    for (std::size_t k = 0; k < segments; ++k) {
      const auto& piece = model.collision[k];
      const auto& p = o.profile[k];
      const auto& q = o.profile[k + 1];
      ASSERT_TRUE(piece.isRound()) << o.name << " " << k;
      const auto& g = *piece.geometry;
      if (p.r == q.r) {
        EXPECT_EQ(g.type(), GeometryType::kCylinder) << o.name << " " << k;
        EXPECT_EQ(g.parameters(), (std::vector<double>{p.r, q.z - p.z})) << o.name << " " << k;
      } else {
        EXPECT_EQ(g.type(), GeometryType::kFrustum) << o.name << " " << k;
        EXPECT_EQ(g.parameters(), (std::vector<double>{p.r, q.r, q.z - p.z})) << o.name << " " << k;
      }
      EXPECT_TRUE(piece.X_OG.linear().isIdentity(0.0)) << o.name << " " << k;
      EXPECT_EQ(piece.X_OG.translation(), Eigen::Vector3d(0.0, 0.0, (p.z + q.z) / 2.0));
      // The triangles are the primitive's polygon in the object frame.
      for (const auto& v : piece.triangles->vertices) {
        EXPECT_GE(v.z(), p.z - 1e-15);
        EXPECT_LE(v.z(), q.z + 1e-15);
      }
    }
    for (std::size_t k = segments; k < model.collision.size(); ++k) {
      EXPECT_FALSE(model.collision[k].isRound()) << o.name << " handle piece " << k;
    }
    // The exact solids change the inertia by less than 1 % against the 32-sided pieces.
    std::vector<rw::geometry::PlacedGeometry> tessellated;
    for (const auto& piece : model.collision) {
      tessellated.push_back({rw::geometry::Geometry::mesh(piece.triangles, "tessellated"),
                             rw::math::Transform3D::Identity()});
    }
    const auto old = rw::geometry::estimateMassProperties(o.mass, tessellated);
    EXPECT_EQ(model.mass.mass, o.mass);
    EXPECT_LT((model.mass.cog - old.cog).norm(), 1e-4) << o.name;
    EXPECT_LT((model.mass.inertia - old.inertia).norm() / old.inertia.norm(), 0.01) << o.name;
    std::ostringstream inertia;
    inertia << model.mass.inertia.diagonal().transpose() << " (32-gon "
            << old.inertia.diagonal().transpose() << ")";
    RecordProperty(o.name + "_inertia", inertia.str());
  }
  EXPECT_GE(lathes, 10);
}

TEST(ObjectModel, TablesArePlainAndCluttered) {
  const auto plain = visgrab::objects::generateTable(*projectSpec().findTable("plain"));
  const auto textured = visgrab::objects::generateTable(*projectSpec().findTable("textured"));
  for (const auto* t : {&plain, &textured}) {
    EXPECT_NEAR(t->x, 1.2, 1e-12);
    EXPECT_NEAR(t->y, 0.8, 1e-12);
    ASSERT_TRUE(t->surface.texture);
    for (const auto& n : t->surface.normals) EXPECT_EQ(n, Eigen::Vector3f(0, 0, 1));
    double area = 0.0;
    for (const auto& tri : t->surface.triangles) {
      const auto& p = t->surface.positions;
      area += 0.5 * (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]).z();
    }
    EXPECT_NEAR(area, t->x * t->y, 1e-5);  // positive: wound counter-clockwise from above
  }
  const auto plainStd = localStdDev(*plain.surface.texture);
  const auto texturedStd = localStdDev(*textured.surface.texture);
  double plainMean = 0.0;
  for (double s : plainStd) plainMean += s / plainStd.size();
  std::size_t busy = 0;
  for (double s : texturedStd) busy += s > 10.0;
  EXPECT_LT(plainMean, 3.0);
  EXPECT_GT(plainMean, 0.2);  // faint grain, not a flat colour
  EXPECT_GT(static_cast<double>(busy) / texturedStd.size(), 0.9);
}

TEST(ObjectModel, GenerationIsDeterministic) {
  const auto& spec = projectSpec().objects.at(4);
  const auto a = visgrab::objects::generateObject(spec);
  const auto b = visgrab::objects::generateObject(spec);
  ASSERT_EQ(a.visual.size(), b.visual.size());
  for (std::size_t i = 0; i < a.visual.size(); ++i) {
    EXPECT_EQ(a.visual[i].mesh.positions, b.visual[i].mesh.positions);
    EXPECT_EQ(a.visual[i].mesh.texture->pixels, b.visual[i].mesh.texture->pixels);
  }
}

TEST(ObjectModel, RejectsAnInvalidSpec) {
  ObjectSpec bad = projectSpec().objects.front();
  bad.mass = 0.0;
  EXPECT_THROW(visgrab::objects::generateObject(bad), std::invalid_argument);
  bad = projectSpec().objects.front();
  bad.boxSize.y() = -0.1;
  EXPECT_THROW(visgrab::objects::generateObject(bad), std::invalid_argument);
}

}  // namespace
