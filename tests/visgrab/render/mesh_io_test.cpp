#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "render_test_util.hpp"
#include "support/test_support.hpp"
#include "visgrab/render/mesh_loader.hpp"
#include "visgrab/render/png_io.hpp"

namespace visgrab::render {
namespace {

using visgrab::test::TempDir;
using visgrab::test::writeFile;

/// Expects `call` to throw std::runtime_error whose message contains every one of `parts`.
template <class Call>
void expectErrorMentioning(Call call, std::initializer_list<std::string> parts) {
  try {
    call();
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    for (const auto& part : parts) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message '" << e.what() << "' lacks '" << part << "'";
    }
  }
}

visual::RgbImage twoByTwo() {
  visual::RgbImage image;
  image.width = 2;
  image.height = 2;
  image.pixels = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  return image;
}

TEST(PngTest, RoundTripKeepsEveryByte) {
  TempDir dir;
  visual::RgbImage image;
  image.width = 7;
  image.height = 3;
  for (int i = 0; i < 7 * 3 * 3; ++i) image.pixels.push_back(static_cast<std::uint8_t>(i * 11));
  for (int level : {0, 3, 9}) {
    const auto path = dir.path() / ("image" + std::to_string(level) + ".png");
    writePng(path, image, level);
    const visual::RgbImage back = readPng(path);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 3);
    EXPECT_TRUE(back.pixels == image.pixels) << "level " << level;
  }
}

TEST(PngTest, TruncatedPngThrowsNamingThePath) {
  TempDir dir;
  visual::RgbImage image;
  image.width = 64;
  image.height = 64;
  for (int i = 0; i < 64 * 64 * 3; ++i) image.pixels.push_back(static_cast<std::uint8_t>(i * 37));
  const auto path = dir.path() / "whole.png";
  writePng(path, image, 0);
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size / 2);
  expectErrorMentioning([&] { readPng(path); }, {path.string()});
}

// Found by fuzzing (fuzz/regressions/png): OpenCV allocated 2.7 GB for a 57-byte PNG whose
// header announced 30000 x 30000 pixels, before it found the pixel data missing.
TEST(PngTest, HugeAnnouncedSizeThrowsBeforeDecoding) {
  TempDir dir;
  visual::RgbImage image;
  image.width = 2;
  image.height = 2;
  image.pixels.assign(12, 200);
  const auto path = dir.path() / "huge.png";
  writePng(path, image, 0);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_EQ(bytes.substr(12, 4), "IHDR");
  const std::string size30000 = {'\0', '\0', static_cast<char>(0x75), static_cast<char>(0x30)};
  bytes.replace(16, 4, size30000);  // width
  bytes.replace(20, 4, size30000);  // height
  writeFile(path, bytes);
  expectErrorMentioning([&] { readPng(path); },
                        {path.string(), "announces 30000 x 30000 pixels", "67108864"});
  expectErrorMentioning([&] { readImage(path); }, {path.string(), "announces 30000 x 30000"});
}

TEST(PngTest, MissingAndNonPngFilesThrowNamingThePath) {
  TempDir dir;
  const auto missing = dir.path() / "missing.png";
  expectErrorMentioning([&] { readPng(missing); }, {missing.string()});
  const auto text = writeFile(dir.path() / "text.png", "not an image at all");
  expectErrorMentioning([&] { readPng(text); }, {text.string(), "not a PNG"});
  const auto nowhere = dir.path() / "no" / "such" / "folder" / "out.png";
  expectErrorMentioning([&] { writePng(nowhere, twoByTwo()); }, {nowhere.string()});
}

/// A textured square: 4 vertices, 2 triangles, OBJ's v-up texture coordinates.
void writeTexturedSquare(const std::filesystem::path& dir, const std::string& textureName) {
  writeFile(dir / "square.obj",
            "mtllib square.mtl\n"
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "vn 0 0 1\n"
            "usemtl painted\n"
            "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n");
  writeFile(dir / "square.mtl",
            "newmtl painted\nKd 0.5 0.25 1.0\nKs 0.2 0.2 0.2\nmap_Kd " + textureName + "\n");
}

TEST(MeshLoaderTest, ObjWithMaterialAndTextureRoundTrip) {
  TempDir dir;
  writeTexturedSquare(dir.path(), "textures/paint.png");
  std::filesystem::create_directories(dir.path() / "textures");
  writePng(dir.path() / "textures" / "paint.png", twoByTwo());

  const auto meshes = loadVisualMeshes(dir.path() / "square.obj");
  ASSERT_EQ(meshes.size(), 1u);
  const visual::VisualMesh& mesh = meshes[0];
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.uvs.size(), 4u);
  ASSERT_EQ(mesh.normals.size(), 4u);
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_NEAR(mesh.colour.x(), 0.5f, 1e-6);
  EXPECT_NEAR(mesh.colour.y(), 0.25f, 1e-6);
  EXPECT_NEAR(mesh.colour.z(), 1.0f, 1e-6);
  EXPECT_NEAR(mesh.specular, 0.2f, 1e-6);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(mesh.normals[i].z(), 1.0f, 1e-6);
    // OBJ's v runs up from the bottom; VisualMesh's runs down from the top: the vertex at
    // y = 1 (vt v = 1, the texture's top edge) gets v = 0.
    const Eigen::Vector3f& p = mesh.positions[i];
    EXPECT_NEAR(mesh.uvs[i].x(), p.x(), 1e-6);
    EXPECT_NEAR(mesh.uvs[i].y(), 1.0f - p.y(), 1e-6);
  }
  ASSERT_TRUE(mesh.texture);
  EXPECT_EQ(mesh.texture->width, 2);
  EXPECT_EQ(mesh.texture->height, 2);
  EXPECT_TRUE(mesh.texture->pixels == twoByTwo().pixels);
}

TEST(MeshLoaderTest, StlWithoutMaterialLoads) {
  TempDir dir;
  const auto path = writeFile(dir.path() / "tri.stl",
                              "solid t\n"
                              "facet normal 0 0 1\nouter loop\n"
                              "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                              "endloop\nendfacet\n"
                              "endsolid t\n");
  const auto meshes = loadVisualMeshes(path);
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_EQ(meshes[0].triangles.size(), 1u);
  EXPECT_TRUE(meshes[0].uvs.empty());
  EXPECT_FALSE(meshes[0].texture);
}

TEST(MeshLoaderTest, MissingFileThrowsNamingIt) {
  TempDir dir;
  const auto path = dir.path() / "absent.obj";
  expectErrorMentioning([&] { loadVisualMeshes(path); }, {path.string(), "does not exist"});
}

TEST(MeshLoaderTest, MissingTextureThrowsNamingBothFiles) {
  TempDir dir;
  writeTexturedSquare(dir.path(), "gone.png");
  const auto path = dir.path() / "square.obj";
  expectErrorMentioning([&] { loadVisualMeshes(path); },
                        {path.string(), (dir.path() / "gone.png").string()});
}

TEST(MeshLoaderTest, GarbageObjThrowsNamingIt) {
  TempDir dir;
  const auto path =
      writeFile(dir.path() / "garbage.obj", "this is not\n\x01\x02 a mesh {{{\nf 9 8 7\n");
  expectErrorMentioning([&] { loadVisualMeshes(path); }, {path.string()});
}

// AC3D visuals (RobWork's device models) keep their MATERIAL's rgb as the mesh colour; the file
// is read by our AC3D reader first, then by assimp for the materials and normals.
TEST(MeshLoaderTest, Ac3dVisualGetsItsMaterialColour) {
  TempDir dir;
  const auto path = writeFile(
      dir.path() / "tri.ac",
      "AC3Db\nMATERIAL \"paint\" rgb 0.25 0.5 0.75  amb 0.2 0.2 0.2  emis 0 0 0  spec 0 0 0  "
      "shi 10  trans 0\nOBJECT world\nkids 1\nOBJECT poly\nname \"tri\"\nloc 1 0 0\nnumvert 3\n"
      "0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\nkids 0\n");
  const auto meshes = loadVisualMeshes(path);
  ASSERT_EQ(meshes.size(), 1u);
  EXPECT_EQ(meshes[0].triangles.size(), 1u);
  EXPECT_NEAR(meshes[0].colour.x(), 0.25f, 1e-6);
  EXPECT_NEAR(meshes[0].colour.y(), 0.5f, 1e-6);
  EXPECT_NEAR(meshes[0].colour.z(), 0.75f, 1e-6);
  ASSERT_EQ(meshes[0].normals.size(), meshes[0].positions.size());
  EXPECT_NEAR(meshes[0].normals[0].z(), 1.0f, 1e-6);  // generated: the triangle faces +z
  for (const Eigen::Vector3f& p : meshes[0].positions) EXPECT_GE(p.x(), 1.0f);  // loc applied
}

// PLY and AC3D files pass our own readers before assimp, STL files the STL check of loadMesh:
// bad ones are refused naming the file and line (assimp looped or allocated without bound on
// some).
TEST(MeshLoaderTest, MalformedPlyAc3dAndStlAreRefusedBeforeAssimp) {
  TempDir dir;
  const auto ply = writeFile(dir.path() / "count.ply",
                             "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
                             "property float y\nproperty float z\nend_header\n0 0 0\n");
  expectErrorMentioning([&] { loadVisualMeshes(ply); },
                        {ply.string() + ":3: error:", "announces 4000000000 entries"});
  const auto ac = writeFile(dir.path() / "count.ac", "AC3Db\nOBJECT poly\nnumvert 900000000\n");
  expectErrorMentioning([&] { loadVisualMeshes(ac); },
                        {ac.string() + ":3: error:", "numvert 900000000 is too large"});
  std::string stl(84, ' ');
  stl[80] = 9;  // 9 triangles announced, none there
  stl[81] = stl[82] = stl[83] = 0;
  const auto bin = writeFile(dir.path() / "short.stl", stl);
  expectErrorMentioning([&] { loadVisualMeshes(bin); }, {bin.string(), "truncated"});
}

// Every mesh input the fuzzer found (fuzz/regressions/mesh) is an error of the renderer's loader
// too, never an abort inside assimp.
TEST(MeshLoaderTest, EveryMeshFuzzFindingIsAnError) {
  TempDir dir;
  const auto files = visgrab::test::meshFuzzRegressions(dir.path());
  EXPECT_GE(files.size(), 12U);
  for (const auto& file : files) EXPECT_THROW(loadVisualMeshes(file), std::runtime_error) << file;
}

}  // namespace
}  // namespace visgrab::render
