#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <string>

#include "mesh_test_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "visgrab/objects/convex_hull.hpp"
#include "visgrab/objects/mesh_object.hpp"
#include "visgrab/objects/object_model.hpp"
#include "visgrab/objects/object_spec.hpp"
#include "visgrab/objects/object_writer.hpp"

namespace {

using rw::common::LoadError;
using visgrab::objects::loadObjectSpecs;
using visgrab::test::TempDir;
using visgrab::test::writeFile;
using visgrab::test::objects::boxMesh;
using visgrab::test::objects::circle;
using visgrab::test::objects::prismMesh;
using visgrab::test::objects::writeObj;

// A spec with one mesh object; `object` holds the attributes after the name, `inner` the
// elements (line 3 is the first of them).
std::filesystem::path writeSpec(const TempDir& dir, const std::string& object,
                                const std::string& inner) {
  return writeFile(dir.path() / "spec" / "objects.xml",
                   "<ObjectDatabase>\n<Object id=\"40\" name=\"thing\" " + object + ">\n" + inner +
                       "\n</Object>\n</ObjectDatabase>\n");
}

visgrab::objects::ObjectModel generateOnly(const std::filesystem::path& spec) {
  return visgrab::objects::generateObject(loadObjectSpecs(spec).objects.at(0));
}

TEST(MeshObject, BoxMassPropertiesMatchTheFormulas) {
  TempDir dir;
  // A 40 x 60 x 100 mm box written in millimetres, away from the file's origin.
  writeObj(dir.path() / "spec" / "meshes" / "box.obj",
           boxMesh({300.0, -200.0, 50.0}, {40.0, 60.0, 100.0}));
  const auto model =
      generateOnly(writeSpec(dir, "density=\"800\"",
                             "<Mesh file=\"meshes/box.obj\" scale=\"0.001\"/>\n"
                             "<Appearance pattern=\"plain-plastic\" seed=\"3\" body=\"0.2 0.4 "
                             "0.6\"/>"));
  const double a = 0.04;
  const double b = 0.06;
  const double c = 0.1;
  const double m = 800.0 * a * b * c;
  EXPECT_NEAR(model.mass.mass, m, 1e-6 * m);
  // The frame: lowest point at z = 0, the centre of mass on the z axis.
  EXPECT_NEAR(model.mass.cog.x(), 0.0, 1e-7);
  EXPECT_NEAR(model.mass.cog.y(), 0.0, 1e-7);
  EXPECT_NEAR(model.mass.cog.z(), c / 2.0, 1e-7);
  const Eigen::Vector3d expected(m / 12.0 * (b * b + c * c), m / 12.0 * (a * a + c * c),
                                 m / 12.0 * (a * a + b * b));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(model.mass.inertia(i, i), expected[i], 1e-5 * expected[i]) << i;
    for (int j = 0; j < 3; ++j) {
      if (i != j) {
        EXPECT_NEAR(model.mass.inertia(i, j), 0.0, 1e-6 * expected[0]);
      }
    }
  }
  const auto bounds = model.collisionBounds();
  EXPECT_NEAR(bounds.min.z(), 0.0, 1e-7);
  EXPECT_NEAR(bounds.max.x() - bounds.min.x(), a, 1e-7);
  // A box is convex: one piece, the box itself.
  ASSERT_EQ(model.collision.size(), 1u);
  EXPECT_NEAR(visgrab::objects::meshVolume(*model.collision[0].triangles), a * b * c, 1e-9);
  // The Appearance is wrapped around the untextured mesh.
  ASSERT_EQ(model.visual.size(), 1u);
  ASSERT_TRUE(model.visual[0].mesh.texture);
  EXPECT_EQ(model.visual[0].mesh.uvs.size(), model.visual[0].mesh.positions.size());
  // Standing, then lying on the four side faces (the box's own frame has z up).
  ASSERT_EQ(model.restingPoses.size(), 5u);
  EXPECT_FALSE(model.restingPoses[0].lying);
  for (std::size_t i = 1; i < 5; ++i) {
    EXPECT_TRUE(model.restingPoses[i].lying);
    EXPECT_NEAR(model.restingPoses[i].up.z(), 0.0, 1e-9);
  }
}

TEST(MeshObject, MassGivenInsteadOfDensityScalesTheInertia) {
  TempDir dir;
  writeObj(dir.path() / "spec" / "box.obj", boxMesh({0, 0, 0}, {0.05, 0.05, 0.2}));
  const auto model = generateOnly(writeSpec(dir, "mass=\"0.3\"", "<Mesh file=\"box.obj\"/>"));
  EXPECT_DOUBLE_EQ(model.mass.mass, 0.3);
  EXPECT_NEAR(model.mass.inertia(2, 2), 0.3 / 12.0 * (2 * 0.05 * 0.05), 1e-9);
}

TEST(MeshObject, CylinderMassPropertiesMatchTheFormulas) {
  TempDir dir;
  const double r = 0.03;
  const double h = 0.12;
  const int sides = 720;
  writeObj(dir.path() / "spec" / "cyl.obj", prismMesh(circle(r, sides), h));
  const auto model =
      generateOnly(writeSpec(dir, "density=\"1000\"", "<Mesh file=\"cyl.obj\" maxPieces=\"1\"/>"));
  // The polygon's area is within (2 pi / sides)^2 / 6 (1.3e-5) of the circle's.
  const double m = 1000.0 * std::numbers::pi * r * r * h;
  EXPECT_NEAR(model.mass.mass, m, 3e-5 * m);
  EXPECT_NEAR(model.mass.cog.z(), h / 2.0, 1e-8);
  EXPECT_NEAR(model.mass.inertia(2, 2), m * r * r / 2.0, 1e-4 * m * r * r / 2.0);
  const double lateral = m * (3.0 * r * r + h * h) / 12.0;
  EXPECT_NEAR(model.mass.inertia(0, 0), lateral, 1e-4 * lateral);
  EXPECT_NEAR(model.mass.inertia(1, 1), lateral, 1e-4 * lateral);
}

TEST(MeshObject, RpyTurnsTheFileIntoTheObjectFrame) {
  TempDir dir;
  // Long along the file's y axis; rpy 0 0 90 (RobWork's order: about z, y, x) turns it about x,
  // y into z (standing).
  writeObj(dir.path() / "spec" / "bar.obj", boxMesh({0, 0, 0}, {0.02, 0.15, 0.03}));
  const auto model =
      generateOnly(writeSpec(dir, "mass=\"0.1\"", "<Mesh file=\"bar.obj\" rpy=\"0 0 90\"/>"));
  const auto bounds = model.collisionBounds();
  EXPECT_NEAR(bounds.max.z() - bounds.min.z(), 0.15, 1e-7);
  EXPECT_NEAR(bounds.max.y() - bounds.min.y(), 0.03, 1e-7);
}

TEST(MeshObject, GivenCollisionPiecesAreKeptOrReplacedByTheirHulls) {
  TempDir dir;
  writeObj(dir.path() / "spec" / "box.obj", boxMesh({0, 0, 0}, {0.1, 0.1, 0.1}));
  writeObj(dir.path() / "spec" / "lower.obj", boxMesh({0, 0, 0}, {0.1, 0.1, 0.05}));
  // An L-shaped prism: not convex, so its hull (a pentagonal prism) is used.
  writeObj(dir.path() / "spec" / "upper.obj",
           prismMesh({{0, 0}, {0.1, 0}, {0.1, 0.05}, {0.05, 0.05}, {0.05, 0.1}, {0, 0.1}}, 0.1));
  const auto model =
      generateOnly(writeSpec(dir, "mass=\"1\"",
                             "<Mesh file=\"box.obj\"/>\n<CollisionPiece file=\"lower.obj\"/>\n"
                             "<CollisionPiece file=\"upper.obj\"/>"));
  ASSERT_EQ(model.collision.size(), 2u);
  EXPECT_NEAR(visgrab::objects::meshVolume(*model.collision[0].triangles), 0.1 * 0.1 * 0.05, 1e-9);
  EXPECT_NEAR(visgrab::objects::meshVolume(*model.collision[1].triangles),
              0.1 * 0.1 * 0.1 - 0.05 * 0.05 * 0.1 / 2.0, 1e-9);
  ASSERT_EQ(model.notes.size(), 2u);
  EXPECT_NE(model.notes[0].find("lower.obj: convex"), std::string::npos) << model.notes[0];
  EXPECT_NE(model.notes[1].find("upper.obj: not convex"), std::string::npos) << model.notes[1];
  EXPECT_NE(model.notes[1].find("replaced by its convex hull"), std::string::npos);
}

TEST(MeshObject, ATexturedMeshKeepsItsOwnTexture) {
  TempDir dir;
  // A box OBJ with texture coordinates and an MTL naming a 5 x 3 PNG.
  const auto box = boxMesh({0, 0, 0}, {0.05, 0.05, 0.05});
  std::string obj = "mtllib box.mtl\nusemtl painted\n";
  for (const auto& v : box.vertices) {
    obj += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
           std::to_string(v.z()) + "\n";
  }
  obj += "vt 0 0\nvt 1 0\nvt 1 1\n";
  for (const auto& t : box.triangles) {
    obj += "f " + std::to_string(t[0] + 1) + "/1 " + std::to_string(t[1] + 1) + "/2 " +
           std::to_string(t[2] + 1) + "/3\n";
  }
  writeFile(dir.path() / "spec" / "box.obj", obj);
  writeFile(dir.path() / "spec" / "box.mtl", "newmtl painted\nKd 1 1 1\nmap_Kd box.png\n");
  visgrab::visual::RgbImage image;
  image.width = 5;
  image.height = 3;
  image.pixels.assign(5 * 3 * 3, 200);
  visgrab::objects::writePng(image, dir.path() / "spec" / "box.png");
  // The Appearance is not used: the file brings its texture.
  const auto model =
      generateOnly(writeSpec(dir, "mass=\"0.1\"",
                             "<Mesh file=\"box.obj\"/>\n<Appearance pattern=\"plain-plastic\" "
                             "seed=\"1\" body=\"1 0 0\"/>"));
  ASSERT_EQ(model.visual.size(), 1u);
  ASSERT_TRUE(model.visual[0].mesh.texture);
  EXPECT_EQ(model.visual[0].mesh.texture->width, 5);
  EXPECT_EQ(model.visual[0].mesh.texture->height, 3);
  // The visual mesh is in the object frame too: lowest point at z = 0.
  float lowest = 1.0f;
  for (const auto& p : model.visual[0].mesh.positions) lowest = std::min(lowest, p.z());
  EXPECT_NEAR(lowest, 0.0f, 1e-6f);
}

TEST(MeshObject, FillHolesClosesAnOpenMesh) {
  auto mesh = boxMesh({0, 0, 0}, {1, 1, 1});
  mesh.triangles.pop_back();
  mesh.triangles.erase(mesh.triangles.begin());
  const auto before = visgrab::objects::checkClosure(mesh);
  EXPECT_EQ(before.openEdges, 6);
  EXPECT_EQ(visgrab::objects::fillHoles(mesh), 2);
  EXPECT_TRUE(visgrab::objects::checkClosure(mesh).closed());
  EXPECT_NEAR(visgrab::objects::meshVolume(mesh), 1.0, 1e-12);
}

TEST(MeshObject, ClosureCountsCrowdedAndFlippedEdges) {
  auto mesh = boxMesh({0, 0, 0}, {1, 1, 1});
  std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);  // one triangle wound the wrong way
  const auto flipped = visgrab::objects::checkClosure(mesh);
  EXPECT_EQ(flipped.flippedEdges, 3);
  EXPECT_EQ(flipped.openEdges, 0);
  auto crowded = boxMesh({0, 0, 0}, {1, 1, 1});
  crowded.triangles.push_back(crowded.triangles[0]);
  EXPECT_EQ(visgrab::objects::checkClosure(crowded).crowdedEdges, 3);
}

// One bad input: the spec's inner elements, what is written to the spec folder, the line the
// error must name and a part of its message.
struct BadMesh {
  const char* what;
  std::string object;
  std::string inner;
  int line;
  std::string message;
};

// Names the case in test output (instead of the struct's bytes).
void PrintTo(const BadMesh& bad, std::ostream* out) { *out << bad.what; }

class BadMeshObject : public ::testing::TestWithParam<BadMesh> {};

TEST_P(BadMeshObject, ErrorNamesTheSpecFileAndLine) {
  const BadMesh& bad = GetParam();
  TempDir dir;
  writeObj(dir.path() / "spec" / "box.obj", boxMesh({0, 0, 0}, {0.1, 0.1, 0.1}));
  auto open = boxMesh({0, 0, 0}, {0.1, 0.1, 0.1});
  open.triangles.pop_back();
  writeObj(dir.path() / "spec" / "open.obj", open);
  auto inverted = boxMesh({0, 0, 0}, {0.1, 0.1, 0.1});
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  writeObj(dir.path() / "spec" / "inverted.obj", inverted);
  const auto spec = writeSpec(dir, bad.object, bad.inner);
  try {
    generateOnly(spec);
    FAIL() << bad.what << ": no error";
  } catch (const LoadError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    const auto& d = e.diagnostics().front();
    EXPECT_EQ(std::filesystem::path(d.file), spec.lexically_normal()) << bad.what;
    EXPECT_EQ(d.line, bad.line) << bad.what << ": " << d.format();
    EXPECT_NE(d.message.find(bad.message), std::string::npos) << bad.what << ": " << d.format();
    EXPECT_NE(std::string(e.what()).find(":" + std::to_string(bad.line) + ":"), std::string::npos)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadMeshObject,
    ::testing::Values(
        BadMesh{"missing mesh", "mass=\"1\"", "<Mesh file=\"nowhere/cup.stl\"/>", 3,
                "mesh file \"nowhere/cup.stl\" not found"},
        BadMesh{"missing piece", "mass=\"1\"",
                "<Mesh file=\"box.obj\"/>\n<CollisionPiece file=\"gone.stl\"/>", 4,
                "collision piece file \"gone.stl\" not found"},
        BadMesh{"open mesh", "mass=\"1\"", "<Mesh file=\"open.obj\"/>", 3,
                "is not closed: 3 edges are not shared by exactly two consistently wound "
                "triangles (3 open, 0 shared by more than two, 0 with flipped winding)"},
        BadMesh{"inverted mesh", "mass=\"1\"", "<Mesh file=\"inverted.obj\"/>", 3,
                "encloses a volume of -0.001 m^3; expected a positive volume"},
        BadMesh{"density 0", "density=\"0\"", "<Mesh file=\"box.obj\"/>", 2,
                "attribute density must be positive, got 0"},
        BadMesh{"negative mass", "mass=\"-1\"", "<Mesh file=\"box.obj\"/>", 2,
                "attribute mass must be positive, got -1"},
        BadMesh{"mass and density", "mass=\"1\" density=\"500\"", "<Mesh file=\"box.obj\"/>", 2,
                "give either mass or density, not both"},
        BadMesh{"neither", "", "<Mesh file=\"box.obj\"/>", 2,
                "missing attribute mass (kg) or density (kg/m^3)"},
        BadMesh{"unknown attribute", "mass=\"1\"", "<Mesh file=\"box.obj\" colour=\"red\"/>", 3,
                "colour"},
        BadMesh{"density without a mesh", "density=\"500\"",
                "<Box x=\"0.1\" y=\"0.1\" z=\"0.1\"/>\n<Appearance pattern=\"plain-plastic\" "
                "seed=\"1\" body=\"0.5 0.5 0.5\"/>",
                2, "attribute density needs a <Mesh> shape"},
        BadMesh{"pair of an unknown object", "mass=\"1\"",
                "<Mesh file=\"box.obj\"/>\n</Object>\n<Pair a=\"thing\" b=\"other\"/>\n<Object "
                "id=\"41\" name=\"spare\" mass=\"1\">\n<Mesh file=\"box.obj\"/>",
                5, "no object named \"other\""}),
    [](const ::testing::TestParamInfo<BadMesh>& param) {
      std::string name = param.param.what;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

}  // namespace
