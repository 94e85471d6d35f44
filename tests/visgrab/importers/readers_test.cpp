// The NPY, NPZ, HDF5 and JSON readers on files written by test_files.hpp (independent writers),
// and every error path with its message.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "import_checks.hpp"
#include "support/test_support.hpp"
#include "test_files.hpp"
#include "visgrab/importers/hdf5_file.hpp"
#include "visgrab/importers/json_value.hpp"
#include "visgrab/importers/npy.hpp"
#include "visgrab/importers/npz.hpp"

namespace visgrab::importers {
namespace {

using test::errorOf;
using test::f4;
using test::f8;
using test::npyBytes;

TEST(Npy, ReadsLittleEndianFloat64InCOrder) {
  const NdArray a = parseNpy(npyBytes("<f8", {2, 3}, f8({1, 2, 3, 4, 5, 6})), "a.npy");
  EXPECT_EQ(a.shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(a.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(a.dtype, "<f8");
  EXPECT_EQ(a.shapeText(), "(2, 3)");
}

TEST(Npy, ReadsFloat32AndVersions2And3) {
  for (int major : {2, 3}) {
    const NdArray a = parseNpy(npyBytes("<f4", {3}, f4({0.5f, -1.0f, 2.25f}), false, major), "b");
    EXPECT_EQ(a.values, (std::vector<double>{0.5, -1.0, 2.25})) << major;
    EXPECT_EQ(a.shapeText(), "(3,)");
  }
}

TEST(Npy, FortranOrderIsReturnedInCOrder) {
  // The 2 x 3 matrix [[1 2 3] [4 5 6]] in Fortran order is stored column by column: 1 4 2 5 3 6.
  const NdArray a = parseNpy(npyBytes("<f8", {2, 3}, f8({1, 4, 2, 5, 3, 6}), true), "f.npy");
  EXPECT_EQ(a.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
}

TEST(Npy, BigEndianAndIntegerTypes) {
  // 1.5 as big-endian float64: 3F F8 00 00 00 00 00 00.
  const std::string be("\x3F\xF8\0\0\0\0\0\0", 8);
  EXPECT_EQ(parseNpy(npyBytes(">f8", {1}, be), "be").values[0], 1.5);
  // -2 as little-endian int32: FE FF FF FF; 258 as big-endian int16: 01 02.
  EXPECT_EQ(parseNpy(npyBytes("<i4", {1}, std::string("\xFE\xFF\xFF\xFF", 4)), "i").values[0],
            -2.0);
  EXPECT_EQ(parseNpy(npyBytes(">i2", {1}, std::string("\x01\x02", 2)), "i2").values[0], 258.0);
  EXPECT_EQ(parseNpy(npyBytes("|u1", {2}, std::string("\xFF\x07", 2)), "u").values,
            (std::vector<double>{255, 7}));
  EXPECT_EQ(parseNpy(npyBytes("|b1", {2}, std::string("\x01\x00", 2)), "b").values,
            (std::vector<double>{1, 0}));
  // A scalar: shape ().
  const NdArray s = parseNpy(npyBytes("<f8", {}, f8({7})), "s");
  EXPECT_TRUE(s.shape.empty());
  EXPECT_EQ(s.values, std::vector<double>{7});
}

TEST(Npy, RefusesObjectArraysStructuredAndOtherTypes) {
  EXPECT_HAS(errorOf([] { parseNpy(npyBytes("|O", {1}, std::string(8, '\0')), "o.npy"); }),
             ("o.npy: an object array (dtype '|O'"));
  std::string structured = npyBytes("<f8", {1}, f8({1}));
  structured.replace(structured.find("'<f8'"), 5, "[('a', '<f8')]");
  EXPECT_HAS(errorOf([&] { parseNpy(structured, "r.npy"); }), ("structured"));
  EXPECT_HAS(errorOf([] { parseNpy(npyBytes("<c16", {1}, std::string(16, '\0')), "c"); }),
             ("c: unsupported dtype '<c16'"));
  EXPECT_HAS(errorOf([] { parseNpy(npyBytes("<U3", {1}, std::string(12, '\0')), "u"); }),
             ("unsupported dtype '<U3'"));
}

TEST(Npy, RefusesBadMagicVersionHeaderAndSizes) {
  EXPECT_HAS(errorOf([] { parseNpy("PK\x03\x04 not npy", "x.npy"); }), ("x.npy: not an NPY file"));
  std::string v4 = npyBytes("<f8", {1}, f8({1}));
  v4[6] = 4;
  EXPECT_HAS(errorOf([&] { parseNpy(v4, "v"); }), ("version 4.0 (expected 1.0"));
  // The data is one value short of the shape (2, 2).
  EXPECT_HAS(errorOf([] {
               parseNpy(npyBytes("<f8", {2, 2}, f8({1, 2, 3})), "short.npy");
             }),
             ("short.npy: the data has 24 bytes, expected 32 for shape (2, 2)"));
  EXPECT_HAS(errorOf([] {
               parseNpy(npyBytes("<f8", {1}, f8({1, 2})), "long");
             }),
             ("the data has 16 bytes, expected 8"));
  std::string missing = npyBytes("<f8", {1}, f8({1}));
  missing.replace(missing.find("'fortran_order'"), 15, "'fortran_ordeR'");
  EXPECT_HAS(errorOf([&] { parseNpy(missing, "m"); }), ("unknown key 'fortran_ordeR'"));
  // A header announcing more bytes than the file has.
  std::string truncated = npyBytes("<f8", {1}, "");
  truncated.resize(30);
  EXPECT_HAS(errorOf([&] { parseNpy(truncated, "t"); }), ("t: truncated NPY header"));
  // A shape whose size overflows is refused before anything is allocated.
  EXPECT_HAS(errorOf([] {
               parseNpy(npyBytes("<f8", {1000000000, 1000000000, 1000000000}, ""), "big");
             }),
             ("big: shape too large"));
}

TEST(Npz, ReadsMembersStoredAndDeflated) {
  test::TempDir dir;
  for (bool compress : {false, true}) {
    const auto file = dir.path() / (compress ? "d.npz" : "s.npz");
    test::writeZip(file,
                   {{"grasps.npy", npyBytes("<f8", {2}, f8({1.5, 2.5}))},
                    {"scores.npy", npyBytes("<f4", {1}, f4({0.25f}))}},
                   compress);
    const NpzFile npz = NpzFile::open(file);
    EXPECT_EQ(npz.names(), (std::vector<std::string>{"grasps", "scores"}));
    EXPECT_EQ(npz.array("grasps").values, (std::vector<double>{1.5, 2.5}));
    EXPECT_EQ(npz.array("scores").values, std::vector<double>{0.25});
    EXPECT_HAS(errorOf([&] { npz.array("widths"); }),
               (file.string() + ": no array 'widths' (member widths.npy); it has "
                                "grasps, scores"));
  }
}

TEST(Npz, RefusesNonZipAndBadMembers) {
  test::TempDir dir;
  const auto notZip = test::writeFile(dir.path() / "n.npz", "plain text");
  EXPECT_HAS(errorOf([&] { NpzFile::open(notZip); }),
             (notZip.string() + ": not a zip (.npz) file"));
  EXPECT_HAS(errorOf([&] { NpzFile::open(dir.path() / "absent.npz"); }),
             ("absent.npz: cannot open the file"));
  const auto objects = dir.path() / "o.npz";
  test::writeZip(objects, {{"grasps.npy", npyBytes("|O", {1}, std::string(8, '\0'))}});
  EXPECT_HAS(errorOf([&] { NpzFile::open(objects).array("grasps"); }),
             (objects.string() + ": array 'grasps': an object array"));
  // A zip cut in the middle.
  const auto whole = dir.path() / "w.npz";
  test::writeZip(whole, {{"a.npy", npyBytes("<f8", {64}, f8(std::vector<double>(64, 1.0)))}},
                 false);
  const std::string bytes = readFileBytes(whole, 1 << 20);
  EXPECT_FALSE(
      errorOf([&] { NpzFile::fromBytes(bytes.substr(0, bytes.size() / 2), "cut"); }).empty());
}

TEST(Hdf5, ReadsDatasetsByPathWithShapes) {
  test::TempDir dir;
  const auto file = dir.path() / "t.h5";
  test::writeHdf5(file, {{"grasps/transforms", {2, 2, 2}, {1, 2, 3, 4, 5, 6, 7, 8}},
                         {"grasps/labels", {3}, {1, 0, 1}, true},
                         {"object/mass", {}, {0.5}},
                         {"object/file", {}, {}, false, true, "meshes/Table/x.obj"}});
  const Hdf5File h5 = Hdf5File::open(file);
  const NdArray t = h5.numbers("grasps/transforms", 3);
  EXPECT_EQ(t.shape, (std::vector<std::size_t>{2, 2, 2}));
  EXPECT_EQ(t.values, (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(h5.numbers("grasps/labels").values, (std::vector<double>{1, 0, 1}));
  EXPECT_TRUE(h5.numbers("object/mass").shape.empty());
  EXPECT_EQ(h5.numbers("object/mass").values, std::vector<double>{0.5});
  EXPECT_EQ(h5.text("object/file"), "meshes/Table/x.obj");
  EXPECT_TRUE(h5.hasDataset("grasps/transforms"));
  EXPECT_FALSE(h5.hasDataset("grasps"));
  EXPECT_FALSE(h5.hasDataset("nothing/here"));

  EXPECT_HAS(
      errorOf([&] { h5.numbers("grasps/transforms", 2, "N x 4"); }),
      (file.string() + ": dataset 'grasps/transforms' has shape (2, 2, 2) (expected N x 4)"));
  EXPECT_HAS(errorOf([&] { h5.numbers("grasps/missing", -1, "N labels"); }),
             (file.string() + ": dataset 'grasps/missing' is missing (expected N "
                              "labels)"));
  EXPECT_HAS(errorOf([&] { h5.numbers("object/file"); }), ("is not numeric"));
  EXPECT_HAS(errorOf([&] { h5.text("object/mass"); }), ("dataset 'object/mass' is not a string"));
  EXPECT_HAS(errorOf([&] { h5.numbers("grasps"); }), ("dataset 'grasps' is not a dataset"));
}

TEST(Hdf5, OpensFileImagesAndRefusesOtherFilesQuietly) {
  test::TempDir dir;
  const auto file = dir.path() / "t.h5";
  test::writeHdf5(file, {{"x", {2}, {3, 4}}});
  const std::string bytes = readFileBytes(file, 1 << 20);
  EXPECT_EQ(Hdf5File::fromBytes(bytes, "image").numbers("x").values, (std::vector<double>{3, 4}));
  const auto text = test::writeFile(dir.path() / "n.h5", "not hdf5");
  // HDF5 prints its error stack to stderr unless silenced; the reader reports it as our error.
  ::testing::internal::CaptureStderr();
  const std::string notHdf5 = errorOf([&] { Hdf5File::open(text); });
  const std::string image = errorOf([&] { Hdf5File::fromBytes("not hdf5 either", "mem.h5"); });
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_HAS(notHdf5, (text.string() + ": not an HDF5 file"));
  EXPECT_HAS(image, ("mem.h5: not a readable HDF5 file: HDF5: "));
  EXPECT_EQ(printed, "");
  EXPECT_HAS(errorOf([&] { Hdf5File::open(dir.path() / "absent.h5"); }),
             ("absent.h5: no such file"));
}

TEST(Json, ReadsTheGrammarStrictly) {
  const JsonValue v = parseJson(
      R"({"a": [1, -2.5e1, 0.125], "b": {"c": true, "d": false, "e": null}, "s": "x\n\u00e9"})",
      "j");
  ASSERT_EQ(v.kind, JsonValue::Kind::kObject);
  EXPECT_EQ(v.find("a")->items[1].number, -25.0);
  EXPECT_TRUE(v.find("b")->find("c")->flag);
  EXPECT_FALSE(v.find("b")->find("d")->flag);
  EXPECT_EQ(v.find("b")->find("e")->kind, JsonValue::Kind::kNull);
  EXPECT_EQ(v.find("s")->text, "x\n\xC3\xA9");
  EXPECT_EQ(v.find("nothing"), nullptr);

  EXPECT_EQ(errorOf([] { parseJson("{\"a\": [1, 2,]}", "f.json"); }),
            "f.json:1:13: expected a JSON value");
  EXPECT_EQ(errorOf([] { parseJson("{\"a\": 1,\n \"a\": 2}", "f.json"); }),
            "f.json:2:8: member \"a\" given twice");
  EXPECT_EQ(errorOf([] { parseJson("[01]", "f"); }), "f:1:3: expected ',' or ']' in an array");
  EXPECT_EQ(errorOf([] { parseJson("{} x", "f"); }), "f:1:4: text after the JSON value");
  EXPECT_EQ(errorOf([] { parseJson("\"abc", "f"); }), "f:1:5: unterminated string");
  EXPECT_EQ(errorOf([] { parseJson("1e999", "f"); }), "f:1:6: number 1e999 is out of range");
  EXPECT_EQ(errorOf([] { parseJson(std::string(100, '['), "f"); }),
            "f:1:66: nested more than 64 deep");
  // Found by the json fuzzer's author: a backslash as the text's last byte.
  EXPECT_EQ(errorOf([] { parseJson("\"abc\\", "f"); }), "f:1:6: unterminated string");
  // Below a double's range too (strtod gave 0).
  EXPECT_EQ(errorOf([] { parseJson("[1e-400]", "f"); }), "f:1:8: number 1e-400 is out of range");
}

TEST(Json, CapsTheNumberOfValues) {
  // The array and its 3 numbers are 4 values: a cap of 4 reads it, 3 stops at the third number
  // (the cap keeps a huge file from asking for many times the memory; kMaxJsonValues).
  EXPECT_EQ(parseJson("[1,\n2, 3]", "f", 4).items.size(), 3u);
  EXPECT_EQ(errorOf([] { parseJson("[1,\n2, 3]", "f", 3); }),
            "f:2:4: more than 3 JSON values; a grasp file this large is not read (split it)");
  EXPECT_EQ(kMaxJsonValues, 4194304u);
}

}  // namespace
}  // namespace visgrab::importers
