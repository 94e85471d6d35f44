// Our own AC3D reader (rw/geometry/ac3d_reader.hpp) through loadMesh: hand-written files whose
// triangles are worked out by hand, every malformed-input branch with its line, the inputs the
// fuzzer found, and RobWork's own AC3D device models against the old assimp path.
#include "rw/geometry/ac3d_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mesh_checks.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rw::geometry::loadMesh;
using rw::geometry::MeshLoadError;
using rw::math::Vector3D;
using visgrab::test::expectLocatedError;
using visgrab::test::signedVolume;
using visgrab::test::TempDir;
using visgrab::test::trianglesFrom;
using visgrab::test::trianglesOf;
using visgrab::test::writeFile;

constexpr const char* kMaterials =
    "MATERIAL \"red\" rgb 1 0 0  amb 0.2 0.2 0.2  emis 0 0 0  spec 0 0 0  shi 10  trans 0\n"
    "MATERIAL \"blue\" rgb 0 0 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0 0 0  shi 10  trans 0\n";

/// Two objects under the world: a group (rotated and moved) with a kid "tri" (rotated and moved
/// again) holding one triangle and one line, and a square moved down holding a quad and a
/// closed line. The group carries a data block over two lines whose text looks like keywords.
std::string sceneText() {
  return std::string("AC3Db\n") + kMaterials +
         "OBJECT world\nname \"scene\"\nkids 2\n"
         "OBJECT group\nname \"g\"\ndata 17\nnumvert 99\nkids 7\n"
         "rot 0 -1 0 1 0 0 0 0 1\nloc 1 2 3\nkids 1\n"
         "OBJECT poly\nname \"tri\"\ntexture \"none.png\"\ntexrep 1 1\ncrease 30\n"
         "url \"http://example.org\"\nrot 1 0 0 0 0 -1 0 1 0\nloc 10 0 0\n"
         "numvert 3\n1 0 0\n0 2 0\n0 0 3\n"
         "numsurf 2\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 1 0\n2 0 1\n"
         "SURF 0x2\nmat 1\nrefs 2\n0 0 0\n1 0 0\nkids 0\n"
         "OBJECT poly\nname \"square\"\nloc 0 0 -1\nnumvert 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
         "numsurf 2\nSURF 0x30\nmat 1\nrefs 4\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n"
         "SURF 0x1\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n";
}

// The kid's points go through its own rot (rows 1 0 0 / 0 0 -1 / 0 1 0) and loc (10 0 0), then
// the group's rot (rows 0 -1 0 / 1 0 0 / 0 0 1) and loc (1 2 3): p_world = R_g R_t (p + t_t) + t_g
// (an object with surfaces adds its loc before its rot: RotAndLocOfAnObjectWithSurfaces; here
// R_t leaves t_t where it is, so R_t (p + t_t) = R_t p + t_t).
//   (1,0,0) -> (1,0,0) + (10,0,0) = (11,0,0)  -> (0,11,0) + (1,2,3) = (1,13,3)
//   (0,2,0) -> (0,0,2) + (10,0,0) = (10,0,2)  -> (0,10,2) + (1,2,3) = (1,12,5)
//   (0,0,3) -> (0,-3,0) + (10,0,0) = (10,-3,0) -> (3,10,0) + (1,2,3) = (4,12,3)
// Both rotations are proper (det +1), so the winding stays. The square's quad (convex) is cut at
// corner 0: (0,0,-1) (1,0,-1) (1,1,-1) and (0,0,-1) (1,1,-1) (0,1,-1). Lines give nothing.
// The old assimp path gave exactly these three triangles for this file without the data block
// (assimp 5.2 fails on a data block of more than one line: "An unknown error occurred").
TEST(Ac3dReaderTest, NestedKidsRotAndLocMaterialsLinesAndData) {
  TempDir dir;
  const auto mesh = loadMesh(writeFile(dir.path() / "scene.ac", sceneText()));
  const auto expected =
      trianglesFrom({{Vector3D(1, 13, 3), Vector3D(1, 12, 5), Vector3D(4, 12, 3)},
                     {Vector3D(0, 0, -1), Vector3D(1, 0, -1), Vector3D(1, 1, -1)},
                     {Vector3D(0, 0, -1), Vector3D(1, 1, -1), Vector3D(0, 1, -1)}});
  EXPECT_EQ(trianglesOf(*mesh), expected);
  EXPECT_EQ(mesh->vertices.size(), 7U);
}

// assimp 5.2, which the renderer still draws AC3D with, adds the loc of an object with surfaces
// to its vertices and keeps only its rot in the frame its kids hang from; a group keeps both.
// A poly with rot R (rows 0 -1 0 / 1 0 0 / 0 0 1: (x,y,z) -> (-y,x,z)) and loc L = (1,0,0):
//   its vertices R (p + L): (0,0,0) -> R (1,0,0) = (0,1,0); (0,0,1) -> (0,1,1); (0,1,0) -> (-1,1,0)
//   its kid (loc (0,0,5), no rot) R (q + (0,0,5)), without L: (0,0,0) -> (0,0,5);
//   (1,0,0) -> R (1,0,5) = (0,1,5); (0,1,0) -> R (0,1,5) = (-1,0,5).
// The old assimp path gave these points (checked with the binary of 5301400 on this file); the
// reader had R p + L before (the collision mesh then lay apart from the drawn one).
TEST(Ac3dReaderTest, RotAndLocOfAnObjectWithSurfaces) {
  TempDir dir;
  const std::string tri =
      "numvert 3\n0 0 0\n%\n0 1 0\nnumsurf 1\nSURF 0x10\nmat 0\nrefs 3\n"
      "0 0 0\n1 0 0\n2 0 0\n";
  const auto with = [&tri](const std::string& second) {
    std::string t = tri;
    t.replace(t.find('%'), 1, second);
    return t;
  };
  const std::string text =
      std::string("AC3Db\n") + kMaterials +
      "OBJECT world\nkids 1\nOBJECT poly\nrot 0 -1 0 1 0 0 0 0 1\nloc 1 0 0\n" + with("0 0 1") +
      "kids 1\nOBJECT poly\nloc 0 0 5\n" + with("1 0 0") + "kids 0\n";
  const auto mesh = loadMesh(writeFile(dir.path() / "poly.ac", text));
  EXPECT_EQ(trianglesOf(*mesh),
            trianglesFrom({{Vector3D(0, 1, 0), Vector3D(0, 1, 1), Vector3D(-1, 1, 0)},
                           {Vector3D(0, 0, 5), Vector3D(0, 1, 5), Vector3D(-1, 0, 5)}}));
  // A second vertex list in one object would leave the surfaces read so far pointing into it.
  const std::string twice = std::string("AC3Db\n") + kMaterials +
                            "OBJECT world\nkids 1\nOBJECT poly\n" + with("1 0 0") + with("1 0 0") +
                            "kids 0\n";
  expectLocatedError(writeFile(dir.path() / "twice.ac", twice), ":18",
                     "a second numvert in one object");
}

// Any hex digit after "AC3D" is a version; CRLF line ends and blank lines are fine; a second
// top-level object (a light, with AC3D's hidden/locked flags) gives no triangles.
TEST(Ac3dReaderTest, VersionDigitsLineEndsAndSubdivZero) {
  TempDir dir;
  for (const std::string version : {"AC3Da", "AC3DF", "AC3D9"}) {
    const std::string text = version + "\r\n" + kMaterials +
                             "\r\nOBJECT poly\r\nsubdiv 0\r\nnumvert 3\r\n0 0 0\r\n1 0 0\r\n0 1 "
                             "0\r\nnumsurf 1\r\nSURF 0x20\r\nmat 1\r\nrefs 3\r\n0 0 0\r\n1 0 "
                             "0\r\n2 0 0\r\nkids 0\r\n"
                             "OBJECT light\r\nname \"lamp\"\r\nhidden\r\nlocked\r\nloc 0 0 5\r\n"
                             "kids 0\r\n";
    EXPECT_EQ(loadMesh(writeFile(dir.path() / "v.ac3d", text))->triangles.size(), 1U) << version;
  }
}

/// A world with one poly object whose body lines are `body` (vertices and surface follow).
std::string objectWith(const std::string& body) {
  return std::string("AC3Db\n") + kMaterials + "OBJECT world\nkids 1\nOBJECT poly\n" + body;
}

// Line numbers: AC3Db is line 1, the materials 2 and 3, OBJECT world 4, kids 5, OBJECT poly 6.
TEST(Ac3dReaderTest, MalformedInputNamesTheLine) {
  TempDir dir;
  const auto expect = [&dir](const std::string& text, const std::string& line,
                             const std::string& fragment) {
    expectLocatedError(writeFile(dir.path() / "bad.ac", text), line, fragment);
  };
  const std::string tri = "numvert 3\n0 0 0\n1 0 0\n0 1 0\n";  // lines 7-10
  const std::string surf = "numsurf 1\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\n";
  expect("AC3X\n", ":1", "expected \"AC3D\" and a hex version digit");
  expect("AC3Dg\n", ":1", "expected \"AC3D\" and a hex version digit");
  expect("AC3Db\nPOLY 1\n", ":2", "expected MATERIAL or OBJECT, found \"POLY\"");
  expect("AC3Db\nMATERIAL \"m\" amb 1 1 1\n", ":2", "expected \"MATERIAL \"<name>\" rgb");
  expect("AC3Db\nMATERIAL \"m rgb 1 1 1\n", ":2", "a string without its closing '\"'");
  expect("AC3Db\nOBJECT box\nkids 0\n", ":2", "expected \"OBJECT world\", \"OBJECT poly\"");
  expect(objectWith("colour 1\n"), ":7", "unknown object keyword \"colour\"");
  expect(objectWith(tri), ":10", "the file ends inside the OBJECT of line 6; expected \"kids");
  expect(objectWith("numvert 3\n0 0 0\n"), ":7", "numvert 3 is too large; expected at most 1");
  expect(objectWith("numvert 2\n0 0 0\n1 x 0\nkids 0\n"), ":9",
         "expected a finite number for a vertex coordinate, found \"x\"");
  expect(objectWith("numvert 2\n0 0 0\n1e39 0 0\nkids 0\n"), ":9", "vertex 1 is not finite");
  expect(objectWith("numvert 2\n0 0 0\n1 0\nkids 0\n"), ":9", "expected a vertex \"<x> <y> <z>\"");
  expect(objectWith("rot 1 0 0 0 1 0 0 0\nkids 0\n"), ":7", "expected \"rot <9 numbers");
  expect(objectWith("loc 1 nan 0\nkids 0\n"), ":7", "expected a finite number for loc");
  expect(objectWith("subdiv 2\nkids 0\n"), ":7",
         "subdiv 2: subdivision surfaces are not supported; expected subdiv 0");
  expect(objectWith("data 500\nabc\nkids 0\n"), ":7", "data of 500 bytes, but only 11 bytes");
  expect(objectWith(tri + "numsurf 900\n" + surf.substr(10) + "kids 0\n"), ":11",
         "numsurf 900 is too large");
  expect(objectWith(tri + "numsurf 1\nSURF 0x1g\nrefs 0\nkids 0\n"), ":12",
         "expected surface flags such as 0x10, found \"0x1g\"");
  expect(objectWith(tri + "numsurf 1\nSURF 0x13\nrefs 0\nkids 0\n"), ":12",
         "surface type 3; expected 0 (polygon), 1 (closed line) or 2 (line)");
  expect(objectWith(tri + "numsurf 1\nSURF 0x10\nmat 2\nrefs 0\nkids 0\n"), ":13",
         "material index 2 is too large; expected at most 1");
  expect(objectWith(tri + "numsurf 1\nSURF 0x10\nnorm 2\nkids 0\n"), ":13",
         "expected \"refs <count>\", found \"norm\"");
  expect(objectWith(tri + "numsurf 1\nSURF 0x10\nrefs 0\nkids 0\n"), ":13",
         "a polygon surface with refs 0; expected at least one corner");
  expect(objectWith(tri + "numsurf 1\nSURF 0x10\nrefs 300\n0 0 0\nkids 0\n"), ":13",
         "refs 300 is too large");
  expect(objectWith(tri + "numsurf 1\nSURF 0x10\nrefs 3\n0 0 0\n1 0 0\n3 0 0\nkids 0\n"), ":16",
         "vertex index 3 is too large; expected at most 2");
  expect(objectWith(tri + "numsurf 1\nSURF 0x10\nrefs 3\n0 0 0\n1 0\n2 0 0\nkids 0\n"), ":15",
         "expected a surface corner \"<vertex index> <u> <v>\"");
  expect(objectWith("kids 1\nname \"x\"\nkids 0\n"), ":8", "expected OBJECT, found \"name\"");
  expect(objectWith("kids 9\n"), ":7", "kids 9 is too large; expected at most 0");
  expect(std::string("AC3Db\nOBJECT poly\nnumvert 1\n0 0 0\nnumsurf 1\nSURF 0\nmat 0\n"), ":7",
         "mat refers to a material, but no MATERIAL comes before it");
}

// Kids nested 64 deep are read; 65 are refused (no stack overflow on deeper files).
TEST(Ac3dReaderTest, NestingDeeperThan64IsAnError) {
  TempDir dir;
  const auto nested = [](int depth) {
    std::string text = std::string("AC3Db\n") + kMaterials;
    for (int d = 0; d < depth; ++d) text += "OBJECT group\nkids 1\n";
    return text +
           "OBJECT poly\nnumvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0\nrefs 3\n"
           "0 0 0\n1 0 0\n2 0 0\nkids 0\n";
  };
  EXPECT_EQ(loadMesh(writeFile(dir.path() / "deep.ac", nested(64)))->triangles.size(), 1U);
  expectLocatedError(writeFile(dir.path() / "deeper.ac", nested(65)), ":134",
                     "objects nested deeper than 64 levels");
}

// A mirroring rot on a kid flips the winding back outward (as the assimp path did).
TEST(Ac3dReaderTest, MirroringRotKeepsOutwardWinding) {
  TempDir dir;
  const std::string text = std::string("AC3Db\n") + kMaterials +
                           "OBJECT world\nkids 1\nOBJECT poly\nrot 0 1 0 1 0 0 0 0 1\n"
                           "numvert 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nnumsurf 4\n"
                           "SURF 0\nrefs 3\n0 0 0\n2 0 0\n1 0 0\n"
                           "SURF 0\nrefs 3\n0 0 0\n1 0 0\n3 0 0\n"
                           "SURF 0\nrefs 3\n0 0 0\n3 0 0\n2 0 0\n"
                           "SURF 0\nrefs 3\n1 0 0\n2 0 0\n3 0 0\nkids 0\n";
  const auto mesh = loadMesh(writeFile(dir.path() / "m.ac", text));
  EXPECT_EQ(mesh->triangles.size(), 4U);
  EXPECT_GT(signedVolume(*mesh), 0.0);
}

// Every input the fuzzer found (fuzz/regressions/mesh: assimp's PLY hangs, its PLY and AC3D
// allocations of tens of GB, its STL leaks, its abort on an empty PLY face) is an error. (That
// none hangs is checked where time is the measure: scripts/fuzz.sh replays each with libFuzzer's
// 10-second timeout; a test asserts no wall-clock time.)
TEST(MeshRegressionTest, EveryFuzzFindingIsAnError) {
  TempDir scratch;
  const auto files = visgrab::test::meshFuzzRegressions(scratch.path());
  EXPECT_GE(files.size(), 12U);
  for (const fs::path& file : files) EXPECT_THROW(loadMesh(file), MeshLoadError) << file;
}

// RobWork's AC3D device models give the same triangles as the old assimp path did. The counts
// and total areas below were computed once with the assimp path (loadMesh at commit 5301400,
// summing |(b - a) x (c - a)| / 2 over the triangles, and the corners); a dump of both paths'
// sorted triangle corners agreed to 7.3e-12 (float rounding of assimp's own number parser).
TEST(MeshLoaderCompatTest, RobWorkAc3dModelsMatchTheAssimpPath) {
  REQUIRE_COMPAT_DATA(data);
  struct Model {
    const char* file;
    std::size_t triangles;
    std::size_t vertices;
    double area;
    Vector3D cornerSum;  // the sum of every triangle's three corners
  };
  const std::vector<Model> models = {
      {"devices/PG70/geometry/basejaw.ac", 12, 8, 0.0013589970548952943,
       Vector3D(0, 2.8749927878379822e-06, 0.18900429095288018)},
      {"devices/PG70/geometry/cube.ac", 1744, 888, 0.064045104250180174,
       Vector3D(-5.9644030421040952, 158.94054476544261, 135.65966641431442)},
      {"devices/Robotiq-2-finger-85/geometry/base.ac", 13316, 6666, 0.049007796684780607,
       Vector3D(29.539196306605845, 648.41325951865861, 329.24329347603077)},
      {"devices/Robotiq-2-finger-85/geometry/finger.ac", 21336, 10630, 0.011399290338432445,
       Vector3D(2962.518796544522, 7165.3274116963148, 710.04448185516867)},
      {"devices/Robotiq-2-finger-85/geometry/inner_link.ac", 1256, 626, 0.0067322245556141139,
       Vector3D(111.12896328233182, 254.59850681945682, 41.86083820910244)},
      {"devices/Robotiq-2-finger-85/geometry/motor_arm.ac", 1076, 538, 0.0045641237246268609,
       Vector3D(143.29863659292459, 128.30948622152209, 35.870847608719487)},
      {"devices/Robotiq-2-finger-85/geometry/outer_link.ac", 1132, 566, 0.0056405108275894367,
       Vector3D(219.79877548292279, 198.36834335699677, 37.738051703898236)}};
  for (const Model& model : models) {
    const auto mesh = loadMesh(data / model.file);
    EXPECT_EQ(mesh->triangles.size(), model.triangles) << model.file;
    EXPECT_EQ(mesh->vertices.size(), model.vertices) << model.file;
    double area = 0.0;
    Vector3D sum = Vector3D::Zero();
    for (const auto& t : mesh->triangles) {
      const Vector3D& a = mesh->vertices[t[0]];
      area += (mesh->vertices[t[1]] - a).cross(mesh->vertices[t[2]] - a).norm() / 2.0;
      sum += a + mesh->vertices[t[1]] + mesh->vertices[t[2]];
    }
    EXPECT_NEAR(area, model.area, 1e-9) << model.file;
    // Each corner within 1e-9 of assimp's: the sums within 1e-9 per corner.
    const double tolerance = 1e-9 * 3.0 * static_cast<double>(model.triangles);
    EXPECT_LT((sum - model.cornerSum).cwiseAbs().maxCoeff(), tolerance) << model.file;
  }
}

}  // namespace
