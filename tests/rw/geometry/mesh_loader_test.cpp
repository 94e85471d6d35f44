#include "rw/geometry/mesh_loader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mesh_checks.hpp"
#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using rw::geometry::Geometry;
using rw::geometry::loadMesh;
using rw::geometry::MeshLoadError;
using rw::geometry::MeshUse;
using rw::geometry::resolveMeshFile;
using rw::geometry::TriMesh;
using rw::math::Vector3D;
using visgrab::test::canonical;
using visgrab::test::expectLocatedError;
using visgrab::test::isClosedAndConsistent;
using visgrab::test::signedVolume;
using visgrab::test::TempDir;
using visgrab::test::Triangle;
using visgrab::test::trianglesOf;
using visgrab::test::writeFile;

/// A tetrahedron with coordinates exact in float; triangles wind outward (zero-based indices).
const std::array<Vector3D, 4> kCorners = {Vector3D(-1.5, 0.25, 0.125), Vector3D(0.5, 0.25, 0.125),
                                          Vector3D(-1.5, 1.25, 0.125), Vector3D(-1.5, 0.25, 2.125)};
const std::array<std::array<int, 3>, 4> kFaces = {{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};

/// The tetrahedron's triangles, each corner moved by `offset`.
std::vector<Triangle> tetrahedron(const Vector3D& offset = Vector3D::Zero()) {
  std::vector<Triangle> result;
  for (const auto& f : kFaces) {
    result.push_back(
        canonical(kCorners[f[0]] + offset, kCorners[f[1]] + offset, kCorners[f[2]] + offset));
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::string asciiStl() {
  std::ostringstream os;
  os << "solid tetra\n";
  for (const auto& f : kFaces) {
    os << " facet normal 0 0 0\n  outer loop\n";
    for (int k : f) os << "   vertex " << kCorners[k].transpose() << "\n";
    os << "  endloop\n endfacet\n";
  }
  os << "endsolid tetra\n";
  return os.str();
}

void appendLittleEndian(std::string& bytes, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>((value >> (8 * i)) & 0xFFU));
}

void appendFloat(std::string& bytes, double value) {
  const auto f = static_cast<float>(value);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  appendLittleEndian(bytes, bits);
}

/// A binary STL of the tetrahedron with the given 80-byte header text (padded with spaces).
std::string binaryStl(const std::string& header) {
  std::string bytes = header;
  bytes.resize(80, ' ');
  appendLittleEndian(bytes, kFaces.size());
  for (const auto& f : kFaces) {
    for (int k = 0; k < 3; ++k) appendFloat(bytes, 0.0);  // normal, unused
    for (int corner : f) {
      for (int k = 0; k < 3; ++k) appendFloat(bytes, kCorners[corner][k]);
    }
    bytes.append(2, '\0');  // attribute byte count
  }
  return bytes;
}

std::string objText() {
  std::ostringstream os;
  os << "# tetrahedron plus a line, which is dropped\no tetra\n";
  for (const Vector3D& v : kCorners) os << "v " << v.transpose() << "\n";
  for (const auto& f : kFaces) os << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
  os << "l 1 2\n";
  return os.str();
}

std::string plyText() {
  std::ostringstream os;
  os << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
     << "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vector3D& v : kCorners) os << v.transpose() << "\n";
  for (const auto& f : kFaces) os << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  return os.str();
}

/// A hand-written AC3D file: world with one poly object, translated by `loc` and with the
/// object rotation `rot` (nine numbers, row by row).
std::string ac3dText(const Vector3D& loc, const std::string& rot = "1 0 0 0 1 0 0 0 1") {
  std::ostringstream os;
  os << "AC3Db\n"
     << "MATERIAL \"grey\" rgb 0.5 0.5 0.5  amb 0.2 0.2 0.2  emis 0 0 0  spec 0 0 0  shi 10  "
        "trans 0\n"
     << "OBJECT world\nkids 1\nOBJECT poly\nname \"tetra\"\n"
     << "rot " << rot << "\n"
     << "loc " << loc.transpose() << "\nnumvert 4\n";
  for (const Vector3D& v : kCorners) os << v.transpose() << "\n";
  os << "numsurf 4\n";
  for (const auto& f : kFaces) {
    os << "SURF 0x10\nmat 0\nrefs 3\n";
    for (int k : f) os << k << " 0 0\n";
  }
  os << "kids 0\n";
  return os.str();
}

/// Expects loadMesh(file) to throw MeshLoadError starting "<file>: error: " and containing
/// `fragment` and the list of expected formats.
void expectLoadError(const fs::path& file, const std::string& fragment) {
  try {
    loadMesh(file);
    ADD_FAILURE() << file << " loaded, expected an error containing: " << fragment;
  } catch (const MeshLoadError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(file.string() + ": error: ", 0), 0U) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_NE(what.find("expected an STL, OBJ, PLY or AC3D file"), std::string::npos) << what;
  }
}

TEST(MeshLoaderTest, LoadsAsciiStlWithJoinedVertices) {
  TempDir dir;
  const auto mesh = loadMesh(writeFile(dir.path() / "tetra.stl", asciiStl()));
  EXPECT_EQ(trianglesOf(*mesh), tetrahedron());
  EXPECT_EQ(mesh->vertices.size(), 4U);
  EXPECT_TRUE(isClosedAndConsistent(*mesh));
  EXPECT_GT(signedVolume(*mesh), 0.0);
}

TEST(MeshLoaderTest, LoadsBinaryStl) {
  TempDir dir;
  const auto mesh = loadMesh(writeFile(dir.path() / "tetra.stl", binaryStl("binary tetra")));
  EXPECT_EQ(trianglesOf(*mesh), tetrahedron());
  EXPECT_EQ(mesh->vertices.size(), 4U);
  EXPECT_TRUE(isClosedAndConsistent(*mesh));
}

TEST(MeshLoaderTest, LoadsBinaryStlWhoseHeaderStartsWithSolid) {
  TempDir dir;
  for (const std::string header : {"solid", "solid tetra exported by a careless tool", "  solid"}) {
    const auto mesh = loadMesh(writeFile(dir.path() / "tetra.stl", binaryStl(header)));
    EXPECT_EQ(trianglesOf(*mesh), tetrahedron()) << "header: " << header;
  }
}

TEST(MeshLoaderTest, LoadsStlUnderRobWorksOtherStlExtensions) {
  TempDir dir;
  EXPECT_EQ(trianglesOf(*loadMesh(writeFile(dir.path() / "a.STL", asciiStl()))), tetrahedron());
  EXPECT_EQ(trianglesOf(*loadMesh(writeFile(dir.path() / "b.stla", asciiStl()))), tetrahedron());
  EXPECT_EQ(trianglesOf(*loadMesh(writeFile(dir.path() / "c.stlb", binaryStl("bin")))),
            tetrahedron());
}

TEST(MeshLoaderTest, LoadsObjDroppingLines) {
  TempDir dir;
  const auto mesh = loadMesh(writeFile(dir.path() / "tetra.obj", objText()));
  EXPECT_EQ(trianglesOf(*mesh), tetrahedron());
  EXPECT_EQ(mesh->vertices.size(), 4U);
}

TEST(MeshLoaderTest, TriangulatesObjQuads) {
  TempDir dir;
  const auto mesh = loadMesh(
      writeFile(dir.path() / "square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  ASSERT_EQ(mesh->triangles.size(), 2U);
  double area = 0.0;
  for (const auto& t : mesh->triangles) {
    const Vector3D& a = mesh->vertices[t[0]];
    const Vector3D n = (mesh->vertices[t[1]] - a).cross(mesh->vertices[t[2]] - a);
    EXPECT_GT(n.z(), 0.0);
    area += n.norm() / 2.0;
  }
  EXPECT_DOUBLE_EQ(area, 1.0);
}

TEST(MeshLoaderTest, LoadsAsciiPly) {
  TempDir dir;
  const auto mesh = loadMesh(writeFile(dir.path() / "tetra.ply", plyText()));
  EXPECT_EQ(trianglesOf(*mesh), tetrahedron());
}

TEST(MeshLoaderTest, LoadsAc3dApplyingObjectLocation) {
  TempDir dir;
  const Vector3D loc(1.0, -2.0, 0.5);
  const auto mesh = loadMesh(writeFile(dir.path() / "tetra.ac", ac3dText(loc)));
  EXPECT_EQ(trianglesOf(*mesh), tetrahedron(loc));
  EXPECT_EQ(mesh->vertices.size(), 4U);
  EXPECT_GT(signedVolume(*mesh), 0.0);
}

TEST(MeshLoaderTest, MirroringNodeTransformKeepsOutwardWinding) {
  TempDir dir;
  const auto mesh = loadMesh(
      writeFile(dir.path() / "mirrored.ac", ac3dText(Vector3D::Zero(), "-1 0 0 0 1 0 0 0 1")));
  std::vector<Triangle> expected;
  const Vector3D flip(-1.0, 1.0, 1.0);
  for (const auto& f : kFaces) {
    expected.push_back(canonical(kCorners[f[0]].cwiseProduct(flip),
                                 kCorners[f[2]].cwiseProduct(flip),
                                 kCorners[f[1]].cwiseProduct(flip)));
  }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(trianglesOf(*mesh), expected);
  EXPECT_GT(signedVolume(*mesh), 0.0);
}

TEST(MeshLoaderTest, ResolvesStlForCollisionAndAc3dForDrawing) {
  TempDir dir;
  writeFile(dir.path() / "geometry/Base.stl", asciiStl());
  writeFile(dir.path() / "geometry/Base.ac", ac3dText(Vector3D::Zero()));
  EXPECT_EQ(resolveMeshFile(dir.path(), "geometry/Base", MeshUse::kCollision),
            dir.path() / "geometry/Base.stl");
  EXPECT_EQ(resolveMeshFile(dir.path(), "geometry/Base", MeshUse::kVisual),
            dir.path() / "geometry/Base.ac");
  // A name that is a file is used as given, whatever the use.
  EXPECT_EQ(resolveMeshFile(dir.path(), "geometry/Base.stl", MeshUse::kVisual),
            dir.path() / "geometry/Base.stl");
}

TEST(MeshLoaderTest, ResolvesInListOrderLowerCaseFirst) {
  TempDir dir;
  writeFile(dir.path() / "z.obj", objText());
  writeFile(dir.path() / "z.dae", "");
  EXPECT_EQ(resolveMeshFile(dir.path(), "z", MeshUse::kCollision), dir.path() / "z.dae");
  EXPECT_EQ(resolveMeshFile(dir.path(), "z", MeshUse::kVisual), dir.path() / "z.obj");
  writeFile(dir.path() / "w.STL", asciiStl());
  EXPECT_EQ(resolveMeshFile(dir.path(), "w", MeshUse::kCollision), dir.path() / "w.STL");
  writeFile(dir.path() / "w.stl", asciiStl());
  EXPECT_EQ(resolveMeshFile(dir.path(), "w", MeshUse::kCollision), dir.path() / "w.stl");
  writeFile(dir.path() / "p.PLY", plyText());
  EXPECT_EQ(resolveMeshFile(dir.path(), "p", MeshUse::kVisual), dir.path() / "p.PLY");
}

TEST(MeshLoaderTest, ResolveSkipsFoldersAndHonoursAbsoluteNames) {
  TempDir dir;
  fs::create_directories(dir.path() / "x");
  writeFile(dir.path() / "x.stl", asciiStl());
  EXPECT_EQ(resolveMeshFile(dir.path(), "x", MeshUse::kCollision), dir.path() / "x.stl");
  TempDir other;
  const std::string absolute = (dir.path() / "x").string();
  EXPECT_EQ(resolveMeshFile(other.path(), absolute, MeshUse::kVisual), dir.path() / "x.stl");
}

TEST(MeshLoaderTest, ResolveReturnsNulloptWhenNothingExists) {
  TempDir dir;
  writeFile(dir.path() / "a.txt", "not a mesh");
  EXPECT_EQ(resolveMeshFile(dir.path(), "a", MeshUse::kCollision), std::nullopt);
  EXPECT_EQ(resolveMeshFile(dir.path(), "missing", MeshUse::kVisual), std::nullopt);
  EXPECT_EQ(resolveMeshFile(dir.path(), "", MeshUse::kVisual), std::nullopt);
}

TEST(MeshLoaderTest, MissingEmptyAndFolderInputsNameTheFile) {
  TempDir dir;
  expectLoadError(dir.path() / "missing.stl", "file not found");
  expectLoadError(writeFile(dir.path() / "empty.stl", ""), "file is empty");
  expectLoadError(writeFile(dir.path() / "empty.obj", ""), "file is empty");
  fs::create_directories(dir.path() / "folder.stl");
  expectLoadError(dir.path() / "folder.stl", "not a regular file");
}

TEST(MeshLoaderTest, TruncatedBinaryStlIsAnError) {
  TempDir dir;
  for (const std::string header : {"binary", "solid but binary"}) {
    std::string bytes = binaryStl(header);
    bytes.resize(bytes.size() - 10);
    expectLoadError(writeFile(dir.path() / "truncated.stl", bytes), "truncated");
  }
  expectLoadError(writeFile(dir.path() / "short.stl", "abc"), "not an STL file");
}

TEST(MeshLoaderTest, BinaryGarbageIsAnErrorNotACrash) {
  TempDir dir;
  std::mt19937 random(20240601U);
  std::string garbage;
  for (int i = 0; i < 4000; ++i) garbage.push_back(static_cast<char>(random() & 0xFFU));
  for (const std::string ext : {".stl", ".obj", ".dae", ".3ds", ".off", ".bin"}) {
    expectLoadError(writeFile(dir.path() / ("garbage" + ext), garbage), "");
  }
  // Our own readers name the line.
  expectLocatedError(writeFile(dir.path() / "garbage.ply", garbage), ":1", "expected \"ply\"");
  expectLocatedError(writeFile(dir.path() / "garbage.ac", garbage), ":1", "expected \"AC3D\"");
  expectLoadError(writeFile(dir.path() / "solid-garbage.stl", "solid " + garbage), "");
}

// Found by fuzzing (fuzz/regressions/mesh): assimp throws for these facets and leaks the mesh it
// was building, so the loader rejects them first.
TEST(MeshLoaderTest, AsciiStlFacetsNeedThreeVerticesOfThreeCoordinates) {
  TempDir dir;
  std::string twoVertices = asciiStl();
  const std::size_t second = twoVertices.find("vertex", twoVertices.find("vertex") + 1);
  twoVertices.erase(second, twoVertices.find('\n', second) + 1 - second);
  expectLoadError(writeFile(dir.path() / "two.stl", twoVertices),
                  "ASCII STL facet 0: has 2 vertices, expected 3");
  std::string shortVertex = asciiStl();
  const std::size_t first = shortVertex.find("vertex");
  const std::size_t lineEnd = shortVertex.find('\n', first);
  shortVertex.replace(first, lineEnd - first, "vertex 0 0");
  expectLoadError(writeFile(dir.path() / "short.stl", shortVertex),
                  "ASCII STL facet 0: vertex 1 has fewer than 3 coordinates");
  expectLoadError(writeFile(dir.path() / "loose.stl", "solid a\nvertex 0 0 0\nendsolid a\n"),
                  "ASCII STL facet 0: vertex outside an outer loop");
  expectLoadError(writeFile(dir.path() / "open.stl", "solid a\nfacet normal 0 0 1\nouter loop\n"),
                  "ASCII STL facet 0: not closed by endfacet at the end of the file");
  expectLoadError(writeFile(dir.path() / "empty.stl", "solid a\nendsolid a\n"),
                  "ASCII STL without a facet");
}

TEST(MeshLoaderTest, NonFiniteCoordinatesAreAnError) {
  TempDir dir;
  for (const std::string bad : {"nan", "inf", "1e999"}) {
    std::string text = asciiStl();
    text.replace(text.find("0.5"), 3, bad);
    expectLoadError(writeFile(dir.path() / "bad.stl", text), "non-finite coordinate");
  }
}

TEST(MeshLoaderTest, FileWithoutTrianglesIsAnError) {
  TempDir dir;
  expectLoadError(writeFile(dir.path() / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n"),
                  "no triangles");
}

/// A tetrahedron as binary little-endian PLY (float vertices, uchar-counted int face lists).
std::string binaryPly() {
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4\n"
      "property list uchar int vertex_indices\nend_header\n";
  const auto append = [&bytes](const auto value) {
    char raw[sizeof(value)];
    std::memcpy(raw, &value, sizeof(value));
    bytes.append(raw, sizeof(value));
  };
  for (const std::array<float, 3>& v :
       {std::array<float, 3>{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) {
    for (const float c : v) append(c);
  }
  for (const std::array<std::int32_t, 3>& f :
       {std::array<std::int32_t, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
    append(std::uint8_t{3});
    for (const std::int32_t i : f) append(i);
  }
  return bytes;
}

TEST(MeshLoaderTest, LoadsBinaryPly) {
  TempDir dir;
  const auto mesh = loadMesh(writeFile(dir.path() / "tetra.ply", binaryPly()));
  EXPECT_EQ(mesh->vertices.size(), 4U);
  EXPECT_EQ(mesh->triangles.size(), 4U);
}

// Found by fuzzing (fuzz/regressions/mesh): counts that cannot fit in the file made assimp
// allocate tens of gigabytes before it noticed; our reader checks them against the bytes left.
TEST(MeshLoaderTest, PlyCountsLargerThanTheFileAreAnError) {
  TempDir dir;
  const std::string vertexHeader =
      "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n";
  expectLocatedError(writeFile(dir.path() / "count.ply", vertexHeader), ":3",
                     "element \"vertex\" announces 4000000000 entries of at least 6 bytes each, "
                     "but only 6 bytes follow the header; expected at most 1");
  std::string binary = binaryPly();
  binary.replace(binary.find("face 4"), 6, "face 300000000");
  expectLocatedError(writeFile(dir.path() / "faces.ply", binary), ":7",
                     "element \"face\" announces 300000000 entries of at least 1 bytes each");
  const std::string list =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nproperty list uint float extra\nend_header\n0 0 0 4000000000 1 2\n";
  expectLocatedError(
      writeFile(dir.path() / "list.ply", list), ":9",
      "element \"vertex\" entry 0, property \"extra\": a list of 4000000000 items is "
      "longer than the rest of the file (5 bytes) could hold");
  std::string binaryList = binaryPly();
  binaryList[binaryList.size() - 13] = static_cast<char>(200);  // last face: 200 indices
  const std::size_t listAt = binaryList.size() - 13;
  expectLocatedError(writeFile(dir.path() / "binary-list.ply", binaryList), "",
                     "error: at byte " + std::to_string(listAt) +
                         ": element \"face\" entry 3, property \"vertex_indices\": a list of 200 "
                         "items is longer than the rest of the file (12 bytes) could hold");
}

TEST(MeshLoaderTest, LoadsFromSeveralThreadsAtOnce) {
  TempDir dir;
  const std::vector<fs::path> files = {writeFile(dir.path() / "a.stl", asciiStl()),
                                       writeFile(dir.path() / "b.stl", binaryStl("bin")),
                                       writeFile(dir.path() / "c.obj", objText()),
                                       writeFile(dir.path() / "d.ply", plyText())};
  constexpr int kThreads = 8;
  constexpr int kRounds = 10;
  std::vector<int> correct(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&files, &correct, t] {
      for (int round = 0; round < kRounds; ++round) {
        for (const fs::path& file : files) {
          if (trianglesOf(*loadMesh(file)) == tetrahedron()) ++correct[t];
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(correct[t], kRounds * 4) << "thread " << t;
}

TEST(MeshLoaderCompatTest, Sdh2ConvexHullsLoadAndAreConvex) {
  REQUIRE_COMPAT_DATA(data);
  // Triangle counts are the counts stored at byte 80 of each binary STL.
  const std::vector<std::pair<std::string, std::size_t>> hulls = {{"Base_hull", 1032},
                                                                  {"FingerBase_hull", 500},
                                                                  {"FingerMid_hull", 566},
                                                                  {"FingerTip_hull", 1376},
                                                                  {"schunkFlance_hull", 188}};
  const fs::path dir = data / "devices/SDH2";
  for (const auto& [name, count] : hulls) {
    const auto file = resolveMeshFile(dir, "geometry/" + name, MeshUse::kCollision);
    ASSERT_TRUE(file.has_value()) << name;
    EXPECT_EQ(*file, dir / ("geometry/" + name + ".stl"));
    const auto mesh = loadMesh(*file);
    EXPECT_EQ(mesh->triangles.size(), count) << name;
    EXPECT_GT(signedVolume(*mesh), 0.0) << name;
    EXPECT_TRUE(isClosedAndConsistent(*mesh)) << name;
    EXPECT_TRUE(Geometry::mesh(mesh, file->string())->isConvex()) << name;
  }
}

TEST(MeshLoaderCompatTest, Pg70MeshesAndPlaneLoad) {
  REQUIRE_COMPAT_DATA(data);
  const fs::path dir = data / "devices/PG70";
  // cube.stl is ASCII with 24 facets (two boxes of 12); cube.ac has 1744 three-corner SURFs.
  EXPECT_EQ(resolveMeshFile(dir, "geometry/cube", MeshUse::kCollision), dir / "geometry/cube.stl");
  EXPECT_EQ(resolveMeshFile(dir, "geometry/cube", MeshUse::kVisual), dir / "geometry/cube.ac");
  EXPECT_EQ(loadMesh(dir / "geometry/cube.stl")->triangles.size(), 24U);
  EXPECT_EQ(loadMesh(dir / "geometry/cube.ac")->triangles.size(), 1744U);
  // plane_5x5.stl: two facets spanning +-2.5 m at z = 0.
  const auto plane = loadMesh(data / "objects/plane_5x5.stl");
  EXPECT_EQ(plane->triangles.size(), 2U);
  const auto bounds = Geometry::mesh(plane, "plane_5x5.stl")->bounds();
  EXPECT_EQ(bounds.min, Vector3D(-2.5, -2.5, 0.0));
  EXPECT_EQ(bounds.max, Vector3D(2.5, 2.5, 0.0));
}

}  // namespace
