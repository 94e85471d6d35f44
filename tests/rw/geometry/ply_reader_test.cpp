// Our own PLY reader (rw/geometry/ply_reader.hpp) through loadMesh: hand-written files whose
// triangles are worked out by hand, and every malformed-input branch with its line or byte.
#include "rw/geometry/ply_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "mesh_checks.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "support/test_support.hpp"

namespace {

using rw::geometry::loadMesh;
using rw::math::Vector3D;
using visgrab::test::expectLocatedError;
using visgrab::test::TempDir;
using visgrab::test::trianglesFrom;
using visgrab::test::trianglesOf;
using visgrab::test::writeFile;

/// The header of a PLY with element vertex (float x y z) and element face (uchar/int lists).
std::string header(const std::string& format, int vertices, int faces) {
  return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
         std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
}

// A quad 0 1 2 3 (convex: cut from corner 0, as assimp does) and a triangle 0 1 4, with a
// comment, obj_info, extra vertex properties (normal, colour), an extra element with a list
// before the faces and one after them, and vertex_index as the list's name.
TEST(PlyReaderTest, AsciiWithExtraElementsPropertiesAndAQuad) {
  TempDir dir;
  const std::string text =
      "ply\r\nformat ascii 1.0\ncomment made by hand\nobj_info nothing\nelement vertex 5\n"
      "property float x\nproperty float nx\nproperty double y\nproperty uchar red\n"
      "property int z\nelement material 2\nproperty list uchar float shades\n"
      "property ushort id\nelement face 2\nproperty uchar flags\n"
      "property list uint8 uint32 vertex_index\nelement edge 1\nproperty int a\n"
      "property int b\nend_header\n"
      "0 9 0 255 0\n2 9 0 255 0\n2 9 1 255 0\n0 9 1 255 0\n1 9 0.5 255 3\n"
      "3 0.5 0.5 0.5 7\n0 8\n"
      "1 4 0 1 2 3\n0 3 0 1 4\n"
      "0 1\n";
  const auto mesh = loadMesh(writeFile(dir.path() / "extra.ply", text));
  // Vertices: v0 (0,0,0), v1 (2,0,0), v2 (2,1,0), v3 (0,1,0), v4 (1,0.5,3).
  // Quad -> (v0 v1 v2), (v0 v2 v3); triangle (v0 v1 v4).
  const Vector3D v0(0, 0, 0), v1(2, 0, 0), v2(2, 1, 0), v3(0, 1, 0), v4(1, 0.5, 3);
  EXPECT_EQ(trianglesOf(*mesh), trianglesFrom({{v0, v1, v2}, {v0, v2, v3}, {v0, v1, v4}}));
  EXPECT_EQ(mesh->vertices.size(), 5U);
}

/// Appends `value` to `bytes` in the given byte order.
template <typename T>
void put(std::string& bytes, T value, bool bigEndian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
  bytes.append(raw, sizeof(T));
}

/// A binary PLY whose x is double, y short, z uchar, with an extra int8 property after z, an
/// extra element with a list before the faces, faces as ushort-counted int lists with a float
/// property after the list: a pyramid over a rectangle given as a quad (and two of its sides).
std::string binaryPly(bool bigEndian) {
  std::string bytes = std::string("ply\nformat ") +
                      (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex 5\nproperty double x\nproperty short y\n"
                      "property uchar z\nproperty int8 extra\nelement junk 2\n"
                      "property list int16 float64 values\nelement face 3\n"
                      "property list ushort int32 vertex_indices\nproperty float32 quality\n"
                      "end_header\n";
  const std::vector<std::array<double, 3>> vertices = {
      {0, 0, 0}, {4, 0, 0}, {4, -5, 0}, {0, -5, 0}, {2, -2, 6}};
  for (const auto& v : vertices) {
    put(bytes, v[0], bigEndian);
    put(bytes, static_cast<std::int16_t>(v[1]), bigEndian);
    put(bytes, static_cast<std::uint8_t>(v[2]), bigEndian);
    put(bytes, std::int8_t{-1}, bigEndian);
  }
  put(bytes, std::int16_t{2}, bigEndian);  // junk 0: two doubles
  put(bytes, 1.5, bigEndian);
  put(bytes, 2.5, bigEndian);
  put(bytes, std::int16_t{0}, bigEndian);  // junk 1: empty list
  const std::vector<std::vector<std::int32_t>> faces = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}};
  for (const auto& f : faces) {
    put(bytes, static_cast<std::uint16_t>(f.size()), bigEndian);
    for (const std::int32_t i : f) put(bytes, i, bigEndian);
    put(bytes, 0.25F, bigEndian);
  }
  return bytes;
}

// Vertices v0 (0,0,0), v1 (4,0,0), v2 (4,-5,0), v3 (0,-5,0), v4 (2,-2,6); the quad 0 3 2 1 is
// convex, so it is cut from its first corner: (v0 v3 v2), (v0 v2 v1); then (v0 v1 v4), (v1 v2 v4).
TEST(PlyReaderTest, BinaryBothEndiannessesMixedTypesAndSkippedLists) {
  TempDir dir;
  const Vector3D v0(0, 0, 0), v1(4, 0, 0), v2(4, -5, 0), v3(0, -5, 0), v4(2, -2, 6);
  const auto expected = trianglesFrom({{v0, v3, v2}, {v0, v2, v1}, {v0, v1, v4}, {v1, v2, v4}});
  for (const bool big : {false, true}) {
    const auto mesh = loadMesh(writeFile(dir.path() / "b.ply", binaryPly(big)));
    EXPECT_EQ(trianglesOf(*mesh), expected) << (big ? "big endian" : "little endian");
  }
}

// assimp's aiProcess_Triangulate: a quad is cut at its concave corner; a convex polygon of more
// corners becomes a fan around its last corner; a concave one is ear-clipped from corner 0 on.
// The expected triangles were also what the assimp path gave for these files (Nov 2026).
TEST(PlyReaderTest, PolygonsAreTriangulatedAsAssimpDid) {
  TempDir dir;
  const auto polygon = [&dir](const std::vector<Vector3D>& corners) {
    std::string text = header("ascii", static_cast<int>(corners.size()), 1);
    for (const Vector3D& c : corners)
      text += std::to_string(c.x()) + " " + std::to_string(c.y()) + " 0\n";
    text += std::to_string(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) text += " " + std::to_string(i);
    return trianglesOf(*loadMesh(writeFile(dir.path() / "p.ply", text + "\n")));
  };
  // Concave at corner 3 (1.5, 0.5): (c3 c0 c1), (c3 c1 c2).
  const Vector3D a(0, 0, 0), b(2, 0, 0), c(2, 2, 0), d(1.5, 0.5, 0);
  EXPECT_EQ(polygon({a, b, c, d}), trianglesFrom({{d, a, b}, {d, b, c}}));
  // Convex pentagon: a fan around corner 4.
  const Vector3D p0(0, 0, 0), p1(2, 0, 0), p2(3, 1, 0), p3(1, 3, 0), p4(-1, 1, 0);
  EXPECT_EQ(polygon({p0, p1, p2, p3, p4}),
            trianglesFrom({{p4, p0, p1}, {p4, p1, p2}, {p2, p3, p4}}));
  // Concave pentagon (corner 3 points inwards): the ears c1 c2 c3, then c3 c4 c0, then c0 c1 c3.
  const Vector3D q0(0, 0, 0), q1(4, 0, 0), q2(4, 4, 0), q3(2, 1, 0), q4(0, 4, 0);
  EXPECT_EQ(polygon({q0, q1, q2, q3, q4}),
            trianglesFrom({{q1, q2, q3}, {q3, q4, q0}, {q0, q1, q3}}));
  // Corners on a line: every corner is flat, which counts as convex: a fan around corner 4.
  const Vector3D l0(0, 0, 0), l1(1, 0, 0), l2(2, 0, 0), l3(3, 0, 0), l4(4, 0, 0);
  EXPECT_EQ(polygon({l0, l1, l2, l3, l4}),
            trianglesFrom({{l4, l0, l1}, {l4, l1, l2}, {l2, l3, l4}}));
  // Not simple (its edges cross): after the ear c4 c0 c1 none is left, and assimp kept only that.
  const Vector3D s0(2, 1, 0), s1(3, 3, 0), s2(4, 0, 0), s3(0, 1, 0), s4(4, 3, 0);
  EXPECT_EQ(polygon({s0, s1, s2, s3, s4}), trianglesFrom({{s4, s0, s1}}));
}

TEST(PlyReaderTest, FacesOfFewerThanThreeCornersAreDropped) {
  TempDir dir;
  const std::string text = header("ascii", 3, 3) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n1 0\n3 0 1 2\n";
  EXPECT_EQ(loadMesh(writeFile(dir.path() / "p.ply", text))->triangles.size(), 1U);
}

TEST(PlyReaderTest, HeaderErrorsNameTheLine) {
  TempDir dir;
  const auto expect = [&dir](const std::string& text, const std::string& line,
                             const std::string& fragment) {
    expectLocatedError(writeFile(dir.path() / "h.ply", text), line, fragment);
  };
  expect("plx\n", ":1", "expected \"ply\" at the start");
  expect("ply 2\n", ":1", "expected the line \"ply\", found \"ply 2\"");
  expect("ply\nformat ascii 1.0\n", ":3", "the header ends without a line \"end_header\"");
  expect("ply\nend_header\n", ":2", "end_header before a \"format\" line");
  expect("ply\nformat ascii 2.0\nend_header\n", ":2", "expected \"format ascii 1.0\"");
  expect("ply\nformat ascii 1.0\nformat ascii 1.0\nend_header\n", ":3", "a second \"format\"");
  expect("ply\nformat ascii 1.0\nelephant 3\nend_header\n", ":3",
         "unknown header line \"elephant 3\"; expected format, element");
  expect("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", ":3",
         "expected \"element <name> <count>\"");
  expect("ply\nformat ascii 1.0\nelement a 0\nelement a 0\nend_header\n", ":4",
         "a second element \"a\"");
  // Triangle strips (assimp made triangles of them) are refused, not dropped unseen.
  expect(
      "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
      "end_header\n3 0 1 2\n",
      ":7", "element tristrips (triangle strips) is not read here");
  expect("ply\nformat ascii 1.0\nproperty float x\nend_header\n", ":3",
         "a property before any element");
  expect("ply\nformat ascii 1.0\nelement a 1\nproperty real x\nend_header\n", ":4",
         "unknown property type \"real\"; expected char, uchar");
  expect("ply\nformat ascii 1.0\nelement a 1\nproperty list float int x\nend_header\n", ":4",
         "a list's count type must be an integer type");
  expect("ply\nformat ascii 1.0\nelement a 1\nproperty float\nend_header\n", ":4",
         "expected \"property <type> <name>\"");
  expect(
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "end_header\n0 0\n",
      ":3", "element vertex needs the scalar properties x, y and z; there is no z");
  expect(
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\n"
      "end_header\n0\n",
      ":3", "element face needs a list property vertex_indices");
}

TEST(PlyReaderTest, AsciiBodyErrorsNameTheLine) {
  TempDir dir;
  const std::string head = header("ascii", 3, 1);  // 9 header lines: the body starts at 10
  const auto expect = [&dir, &head](const std::string& body, const std::string& line,
                                    const std::string& fragment) {
    expectLocatedError(writeFile(dir.path() / "a.ply", head + body), line, fragment);
  };
  expect("0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n", ":11",
         "element \"vertex\" entry 1, property \"y\": expected a number, found \"abc\"");
  expect("0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", ":13",
         "property \"vertex_indices\": expected an integer from 0 to 255, found \"300\"");
  expect("0 0 0\n1 0 0\n0 1 0\n", ":7",
         "element \"face\" announces 1 entries of at least 2 bytes each, but only 18 bytes");
  expect("0 0 0\n1 0 0\n0 1 0\n3 0 1\n\n\n", ":13",
         "the line ends before element \"face\" entry 0, property \"vertex_indices\"; expected "
         "one entry per line");
  expect("0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n", ":13",
         "expected the end of the line after element \"face\" entry 0 (one entry per line), "
         "found \"7\"");
  expect("0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n0 0 0\n", ":15",
         "expected the end of the file after the last element, found \"0 0 0\"");
  // Found by fuzzing the renderer's loader: assimp 5.2's triangulation aborts on an empty face.
  expect("0 0 0\n1 0 0\n0 1 0\n0\n", ":13", "face 0 has no corners");
  expect("0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", ":13",
         "face 0: vertex index -1 is negative; expected an index from 0");
  expect("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":13",
         "face 0: vertex index 3 is out of range; expected an index below 3");
  for (const std::string bad : {"nan", "inf", "1e39"}) {  // 1e39 is infinite in float
    expect("0 0 0\n1 " + bad + " 0\n0 1 0\n3 0 1 2\n", ":11",
           "vertex 1 has a non-finite coordinate (in float); expected finite x, y, z");
  }
  expect("0 0 0\n1 0 0\n0 1 0\n9 0 1 2\n", ":13",
         "a list of 9 items is longer than the rest of the file (7 bytes) could hold");
}

TEST(PlyReaderTest, BinaryBodyErrorsNameTheByte) {
  TempDir dir;
  std::string head = header("binary_little_endian", 3, 1);
  head.insert(head.find("end_header"), "property float quality\n");
  std::string body;
  for (const float c : {0.0F, 0.0F, 0.0F, 1.0F, 0.0F, 0.0F, 0.0F, 1.0F, 0.0F}) put(body, c, false);
  put(body, std::uint8_t{3}, false);
  for (const std::int32_t i : {0, 1, 2}) put(body, i, false);
  const std::size_t faceAt = head.size() + 36;  // after 3 vertices of 12 bytes
  // Without the face's quality the list still fits, the float after it does not.
  expectLocatedError(writeFile(dir.path() / "t.ply", head + body), "",
                     "error: at byte " + std::to_string(faceAt + 13) +
                         ": the file ends inside element \"face\" entry 0, property "
                         "\"quality\"; expected 4 more bytes");
  put(body, 0.5F, false);
  ASSERT_EQ(loadMesh(writeFile(dir.path() / "ok.ply", head + body))->triangles.size(), 1U);
  std::string outOfRange = head + body;
  outOfRange[faceAt + 9] = 7;  // the third index
  expectLocatedError(writeFile(dir.path() / "r.ply", outOfRange), "",
                     "error: at byte " + std::to_string(faceAt) +
                         ": face 0: vertex index 7 is out of range; expected an index below 3");
  std::string nonFinite = head + body;
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(nonFinite.data() + head.size() + 16, &inf, sizeof inf);  // vertex 1, y
  expectLocatedError(writeFile(dir.path() / "n.ply", nonFinite), "",
                     "error: at byte " + std::to_string(head.size() + 12) +
                         ": vertex 1 has a non-finite coordinate");
}

// An element without properties reads nothing, however many entries it announces (no loop).
TEST(PlyReaderTest, ElementWithoutPropertiesTakesNoTime) {
  TempDir dir;
  const std::string text =
      "ply\nformat binary_little_endian 1.0\nelement nothing 18446744073709551615\n"
      "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  expectLocatedError(writeFile(dir.path() / "e.ply", text), "", "no triangles");
}

}  // namespace
