// ACRONYM's .h5 and GraspGen's .json: one grasp worked by hand, the object fields, the labels,
// their errors, and ACRONYM's published table example (../shared/acronym, when present).
#include "visgrab/importers/acronym.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "import_checks.hpp"
#include "support/test_support.hpp"
#include "test_files.hpp"
#include "visgrab/importers/grasp_importers.hpp"

namespace visgrab::importers {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

using test::errorOf;

// Scene "table", method "acronym", the Franka-like jaw frame of import_checks.hpp.
ImportContext acronymContext() { return test::frankaImportContext("table", "acronym"); }

// The mesh frame turned 90 degrees about the world z and at (0.3, 0, 0.2).
Transform3D meshPose() {
  rw::math::Rotation3D R;
  R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  return rw::math::makeTransform(R, Vector3D(0.3, 0, 0.2));
}

// Grasp 0: the hand unrotated at (0, 0, -0.2) in the mesh frame; grasp 1: a 3 x 4 block
// padded to 16 numbers whose last row is not 0 0 0 1.
const std::vector<double> kTwoGrasps{1, 0, 0, 0,   0, 1, 0, 0,   0, 0, 1, -0.2, 0, 0, 0, 1,
                                     1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3,  1, 0, 0, 0};

// X_W_jaw = X_W_mesh X_mesh_hand T(0, 0, 0.1034): in the mesh the pad centre is at
// (0, 0, -0.2 + 0.1034) = (0, 0, -0.0966); turned about z it stays there, so the world position
// is (0.3, 0, 0.2 - 0.0966) = (0.3, 0, 0.1034); the axes are the mesh's: x = (0,1,0),
// y = (-1,0,0), z = (0,0,1).
void expectGraspZeroWorkedByHand(const ImportResult& r, const std::string& file) {
  ASSERT_EQ(r.grasps.size(), 1u);
  const grasp::GraspRequest& g = r.grasps[0];
  rw::math::Rotation3D R;
  R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_TRANSFORM_NEAR(g.X_W_jaw, rw::math::makeTransform(R, Vector3D(0.3, 0, 0.1034)), 1e-12);
  EXPECT_DOUBLE_EQ(g.width, 0.08);
  EXPECT_FALSE(g.score.has_value());
  EXPECT_EQ(g.id, "0");
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0].format(),
            file +
                ": grasp 1: the transform's last row is not 0 0 0 1 (expected a 4x4 "
                "homogeneous transform)");
}

std::vector<test::H5Dataset> tableObject() {
  return {{"object/file", {}, {}, false, true, "meshes/Table/x.obj"},
          {"object/scale", {}, {0.5}},
          {"object/density", {}, {150}},
          {"object/friction", {}, {1.0}},
          {"object/mass", {}, {2.5}},
          {"object/com", {3}, {0.1, 0.2, 0.3}},
          {"object/inertia", {3, 3}, {1, 0.1, 0, 0.1, 2, 0, 0, 0, 3}}};
}

TEST(AcronymImport, OneH5GraspWorkedByHand) {
  test::TempDir dir;
  const auto file = dir.path() / "Table_x_0.5.h5";
  test::writeHdf5(file, {{"grasps/transforms", {2, 4, 4}, kTwoGrasps},
                         {"grasps/qualities/flex/object_in_gripper", {2}, {1, 0}, true}});
  expectGraspZeroWorkedByHand(importAcronym(file, meshPose(), acronymContext()), file.string());
  EXPECT_EQ(readAcronymLabels(file), (std::vector<int>{1, 0}));
}

TEST(AcronymImport, GraspGenJsonWorkedByHand) {
  test::TempDir dir;
  const auto file = test::writeFile(dir.path() / "grasps.json",
                                    R"({"object": {"file": "meshes/Table/x.obj", "scale": 0.5},
 "grasps": {"transforms": [[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, -0.2], [0, 0, 0, 1]],
                           [[1, 0, 0, 0.1], [0, 1, 0, 0.2], [0, 0, 1, 0.3], [1, 0, 0, 0]]],
            "object_in_gripper": [true, false]}})");
  expectGraspZeroWorkedByHand(importAcronym(file, meshPose(), acronymContext()), file.string());
  EXPECT_EQ(readAcronymLabels(file), (std::vector<int>{1, 0}));
}

TEST(AcronymImport, AHandThatOpensLessRejectsEveryGrasp) {
  test::TempDir dir;
  const auto file = dir.path() / "t.h5";
  test::writeHdf5(
      file, {{"grasps/transforms", {1, 4, 4}, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
  ImportContext narrow = acronymContext();
  narrow.hand = "pg70";
  narrow.jaw.stroke = 0.068;
  const ImportResult r = importAcronym(file, Transform3D::Identity(), narrow);
  EXPECT_TRUE(r.grasps.empty());
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0].message,
            "width 0.08 m is more than hand \"pg70\" opens (expected 0 to its stroke 0.068 m)");
}

TEST(AcronymImport, MissingKeysWrongShapesAndBadLabelsRejectTheFile) {
  test::TempDir dir;
  const auto none = dir.path() / "none.h5";
  test::writeHdf5(none, {{"grasps/other", {1}, {0}}});
  EXPECT_EQ(errorOf([&] { importAcronym(none, Transform3D::Identity(), acronymContext()); }),
            none.string() +
                ": dataset 'grasps/transforms' is missing (expected N x 4 x 4 "
                "transforms)");
  const auto flat = dir.path() / "flat.h5";
  test::writeHdf5(flat, {{"grasps/transforms", {2, 16}, std::vector<double>(32, 0.0)}});
  EXPECT_EQ(errorOf([&] { importAcronym(flat, Transform3D::Identity(), acronymContext()); }),
            flat.string() +
                ": dataset 'grasps/transforms' has shape (2, 16) (expected N x 4 x "
                "4 transforms)");
  const auto threeByFour = dir.path() / "t34.h5";
  test::writeHdf5(threeByFour, {{"grasps/transforms", {1, 3, 4}, std::vector<double>(12, 0.0)}});
  EXPECT_EQ(errorOf([&] { importAcronym(threeByFour, Transform3D::Identity(), acronymContext()); }),
            threeByFour.string() +
                ": grasps/transforms has shape (1, 3, 4), expected (N, 4, 4): "
                "the Panda hand's pose in the mesh frame per grasp");
  const auto labels = dir.path() / "labels.h5";
  test::writeHdf5(labels, {{"grasps/transforms", {2, 4, 4}, kTwoGrasps},
                           {"grasps/qualities/flex/object_in_gripper", {3}, {1, 0, 1}, true}});
  EXPECT_EQ(errorOf([&] { readAcronymLabels(labels); }),
            labels.string() +
                ": grasps/qualities/flex/object_in_gripper has 3 labels, "
                "expected 2 (one per grasp)");
  const auto two = dir.path() / "two.h5";
  test::writeHdf5(two, {{"grasps/transforms", {2, 4, 4}, kTwoGrasps},
                        {"grasps/qualities/flex/object_in_gripper", {2}, {1, 2}, true}});
  EXPECT_EQ(errorOf([&] { readAcronymLabels(two); }),
            two.string() +
                ": grasps/qualities/flex/object_in_gripper[1] is 2.000000, expected "
                "0 or 1");
  EXPECT_HAS(errorOf([&] { readAcronymLabels(none); }), "dataset 'grasps/transforms' is missing");
  const auto json = test::writeFile(dir.path() / "g.json", R"({"grasps": {"transforms": [[1]]}})");
  EXPECT_HAS(errorOf([&] { importAcronym(json, Transform3D::Identity(), acronymContext()); }),
             json.string() + ":1:28: grasps.transforms[0] is not a 4x4 matrix");
  const auto noGrasps = test::writeFile(dir.path() / "n.json", R"({"object": {}})");
  EXPECT_HAS(errorOf([&] { importAcronym(noGrasps, Transform3D::Identity(), acronymContext()); }),
             noGrasps.string() + ": no object \"grasps\" (expected GraspGen's layout");
}

TEST(AcronymObjectFields, ReadsEveryField) {
  test::TempDir dir;
  const auto file = dir.path() / "o.h5";
  test::writeHdf5(file, tableObject());
  const AcronymObject o = readAcronymObject(file);
  EXPECT_EQ(o.file, "meshes/Table/x.obj");
  EXPECT_EQ(o.scale, 0.5);
  EXPECT_EQ(o.density, 150.0);
  EXPECT_EQ(o.friction, 1.0);
  EXPECT_EQ(o.mass, 2.5);
  EXPECT_EQ(o.com, Vector3D(0.1, 0.2, 0.3));
  EXPECT_EQ(o.inertia(0, 1), 0.1);
  EXPECT_EQ(o.inertia(2, 2), 3.0);
}

TEST(AcronymObjectFields, EachBadFieldIsNamed) {
  test::TempDir dir;
  struct Case {
    std::string key;
    test::H5Dataset replacement;
    std::string message;
  };
  const std::vector<Case> cases{
      {"object/scale",
       {"object/scale", {}, {0.0}},
       "dataset 'object/scale' is 0.000000, "
       "expected a finite number > 0"},
      {"object/friction",
       {"object/friction", {}, {-1}},
       "dataset 'object/friction' is "
       "-1.000000, expected a finite number "
       ">= 0"},
      {"object/com",
       {"object/com", {2}, {0, 0}},
       "dataset 'object/com' has shape (2,), "
       "expected 3 finite numbers"},
      {"object/inertia",
       {"object/inertia", {3, 3}, {1, 0.5, 0, 0, 2, 0, 0, 0, 3}},
       "dataset 'object/inertia' is not a finite symmetric 3 x 3 matrix"},
      {"object/mass",
       {"object/mass", {2}, {1, 2}},
       "dataset 'object/mass' has shape (2,), "
       "expected one number"},
      {"object/file", {"object/file", {}, {1}}, "dataset 'object/file' is not a string"},
      {"object/density", {"object/unrelated", {}, {1}}, "dataset 'object/density' is missing"}};
  for (const Case& c : cases) {
    std::vector<test::H5Dataset> datasets;
    for (auto d : tableObject()) datasets.push_back(d.path == c.key ? c.replacement : d);
    const auto file = dir.path() / (std::to_string(&c - cases.data()) + ".h5");
    test::writeHdf5(file, datasets);
    EXPECT_EQ(errorOf([&] { readAcronymObject(file); }), file.string() + ": " + c.message) << c.key;
  }
}

TEST(AcronymExample, ReadsTheTableExampleTransformsLabelsAndObject) {
  const auto data = visgrab::test::acronymDataDir();
  const std::filesystem::path file =
      data ? *data / "grasps/Table_99cf659ae2fe4b87b72437fd995483b_0.009700376721042367.h5"
           : std::filesystem::path();
  if (!data || !std::filesystem::exists(file)) {
    GTEST_SKIP() << "ACRONYM's example is not there: set VISGRAB_ACRONYM_DATA or RW_COMPAT_DATA "
                    "(its ../acronym) to run this test";
  }
  const NdArray transforms = readAcronymTransforms(file);
  EXPECT_EQ(transforms.shapeText(), "(2000, 4, 4)");
  const std::vector<int> labels = readAcronymLabels(file);
  ASSERT_EQ(labels.size(), 2000u);
  const int held = std::accumulate(labels.begin(), labels.end(), 0);
  // 78 % of the labels are "held": 1,559 of 2,000 (77.95 %), counted with a few lines of the
  // HDF5 C API outside this reader.
  EXPECT_EQ(held, 1559);
  // Every grasp imports for the Franka: fully open 0.08 m, proper rotations.
  const ImportResult r = importAcronym(file, Transform3D::Identity(), acronymContext());
  EXPECT_EQ(r.grasps.size(), 2000u);
  EXPECT_TRUE(r.rejected.empty());
  // The object: the file name carries its mesh and scale.
  const AcronymObject o = readAcronymObject(file);
  EXPECT_EQ(o.file, "meshes/Table/99cf659ae2fe4b87b72437fd995483b.obj");
  // The file stores the scale to 10 significant digits, the name to 16.
  EXPECT_NEAR(o.scale, 0.009700376721042367, 5e-11);
  EXPECT_GT(o.mass, 0.0);
  // FleX's mass is density x volume of the scaled mesh.
  ASSERT_TRUE(o.volume.has_value());
  EXPECT_NEAR(o.mass, o.density * *o.volume, 1e-6 * o.mass);
}

}  // namespace
}  // namespace visgrab::importers
