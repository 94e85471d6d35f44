// The importers' conventions on one grasp per format worked by hand (in the comments), and every
// error path with its message. Files are written by test_files.hpp.
#include "visgrab/importers/grasp_importers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "import_checks.hpp"
#include "support/test_support.hpp"
#include "test_files.hpp"
#include "visgrab/importers/npy.hpp"

namespace visgrab::importers {
namespace {

using rw::math::Transform3D;
using rw::math::Vector3D;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using test::errorOf;

// Scene "scene1", method "m", the Franka-like jaw frame of import_checks.hpp.
ImportContext frankaContext() { return test::frankaImportContext("scene1", "m"); }

// The camera above the table looking down: its z (forward) along world -z, its x along world x,
// so its y (down in the image) along world -y; at (0.1, 0.2, 0.8).
Transform3D cameraLookingDown() {
  rw::math::Rotation3D R;
  R.col(0) = Vector3D(1, 0, 0);
  R.col(1) = Vector3D(0, -1, 0);
  R.col(2) = Vector3D(0, 0, -1);
  return rw::math::makeTransform(R, Vector3D(0.1, 0.2, 0.8));
}

Transform3D pose(const Vector3D& x, const Vector3D& y, const Vector3D& z, const Vector3D& p) {
  rw::math::Rotation3D R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = z;
  return rw::math::makeTransform(R, p);
}

// One GraspGroup row: score, width, height, depth, R row-major, t, object id.
std::vector<double> graspnetRow(double score, double width, double depth,
                                const std::vector<double>& R, const Vector3D& t) {
  std::vector<double> row{score, width, 0.02, depth};
  row.insert(row.end(), R.begin(), R.end());
  row.insert(row.end(), {t.x(), t.y(), t.z(), 3.0});
  return row;
}

// Approach along the camera's z, closing along its x: the rotation's columns a = (0,0,1),
// b = (1,0,0), c = a x b = (0,1,0); row-major rows (0 1 0), (0 0 1), (1 0 0).
const std::vector<double> kTopDown{0, 1, 0, 0, 0, 1, 1, 0, 0};

TEST(GraspnetImport, OneGraspWorkedByHand) {
  // t = (0.02, -0.01, 0.5) in the camera, depth 0.03: the fingertips' front at t + depth a =
  // (0.02, -0.01, 0.53) (plot_gripper_pro_max draws the fingers up to x = depth). The pad centre
  // is tipDepth = 0.01 behind it: (0.02, -0.01, 0.52). Jaw axes in the camera: x = b = (1,0,0),
  // z = a = (0,0,1), y = z x x = (0,1,0): the identity.
  // In the world: p = (0.1, 0.2, 0.8) + 0.02 (1,0,0) - 0.01 (0,-1,0) + 0.52 (0,0,-1)
  //                 = (0.12, 0.21, 0.28); axes x = (1,0,0), y = (0,-1,0), z = (0,0,-1).
  NdArray a;
  a.shape = {1, 17};
  a.values = graspnetRow(0.9, 0.05, 0.03, kTopDown, Vector3D(0.02, -0.01, 0.5));
  const ImportResult r = importGraspnetArray(a, "g.npy", cameraLookingDown(), frankaContext());
  ASSERT_EQ(r.grasps.size(), 1u);
  EXPECT_TRUE(r.rejected.empty());
  const grasp::GraspRequest& g = r.grasps[0];
  EXPECT_EQ(g.kind, grasp::GraspKind::kJaw);
  EXPECT_EQ(g.id, "0");
  EXPECT_EQ(g.sceneId, "scene1");
  EXPECT_EQ(g.method, "m");
  EXPECT_EQ(g.sourceFile, "g.npy");
  EXPECT_DOUBLE_EQ(g.width, 0.05);
  ASSERT_TRUE(g.score.has_value());
  EXPECT_DOUBLE_EQ(*g.score, 0.9);
  EXPECT_TRANSFORM_NEAR(g.X_W_jaw, pose({1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0.12, 0.21, 0.28}),
                        1e-12);
  // The fingertips' front, tipDepth along the approach: (0.12, 0.21, 0.27), the world image of
  // t + depth a = (0.12, 0.21, 0.30) + 0.03 (0,0,-1).
  EXPECT_VECTOR_NEAR(g.X_W_jaw * Vector3D(0, 0, 0.01), Vector3D(0.12, 0.21, 0.27), 1e-12);
}

TEST(GraspnetImport, ReadsTheNpyFileInFloat32) {
  test::TempDir dir;
  std::vector<double> row = graspnetRow(0.5, 0.04, 0.02, kTopDown, Vector3D(0, 0, 0.4));
  const std::vector<float> asFloat(row.begin(), row.end());
  const auto file = dir.path() / "grasps.npy";
  test::writeFile(file, test::npyBytes("<f4", {1, 17}, test::f4(asFloat)));
  const ImportResult r = importGraspnet(file, Transform3D::Identity(), frankaContext());
  ASSERT_EQ(r.grasps.size(), 1u);
  // Origin t + (depth - tipDepth) a = (0, 0, 0.4 + 0.01), within float precision.
  EXPECT_VECTOR_NEAR(r.grasps[0].X_W_jaw.translation(), Vector3D(0, 0, 0.41), 1e-6);
  EXPECT_NEAR(r.grasps[0].width, 0.04, 1e-7);
}

TEST(GraspnetImport, EachBadGraspIsRejectedWithItsIndexAndTheOthersKept) {
  NdArray a;
  a.shape = {8, 17};
  const Vector3D t(0, 0, 0.4);
  const std::vector<double> scaled{0, 1.1, 0, 0, 0, 1, 1, 0, 0};
  const std::vector<double> mirrored{0, -1, 0, 0, 0, 1, 1, 0, 0};
  std::vector<std::vector<double>> rows{
      graspnetRow(0.9, 0.05, 0.03, kTopDown, t),   // 0: good
      graspnetRow(0.9, 0.1, 0.03, kTopDown, t),    // 1: wider than the stroke
      graspnetRow(0.9, 0.05, 0.03, scaled, t),     // 2: not orthonormal
      graspnetRow(0.9, 0.05, 0.03, mirrored, t),   // 3: a reflection
      graspnetRow(kNaN, 0.05, 0.03, kTopDown, t),  // 4: NaN score
      graspnetRow(0.9, 0.05, -0.01, kTopDown, t),  // 5: negative depth
      graspnetRow(0.9, 0.05, 0.03, kTopDown, t),   // 6: good
      graspnetRow(0.9, 0.05, 0.03, kTopDown, t)};  // 7: NaN object id (unused, still bad)
  rows[7][16] = kNaN;
  for (const auto& row : rows) a.values.insert(a.values.end(), row.begin(), row.end());
  const ImportResult r = importGraspnetArray(a, "g.npy", Transform3D::Identity(), frankaContext());
  ASSERT_EQ(r.grasps.size(), 2u);
  EXPECT_EQ(r.grasps[0].id, "0");
  EXPECT_EQ(r.grasps[1].id, "6");
  ASSERT_EQ(r.rejected.size(), 6u);
  EXPECT_EQ(r.rejected[0].format(),
            "g.npy: grasp 1: width 0.1 m is more than hand \"franka\" opens (expected 0 to its "
            "stroke 0.08 m)");
  EXPECT_EQ(r.rejected[1].format(),
            "g.npy: grasp 2: the rotation is not orthonormal: max |R^T R - I| = 0.21 (expected "
            "at most 0.0001)");
  EXPECT_EQ(r.rejected[2].format(),
            "g.npy: grasp 3: the rotation is a reflection (determinant -1), expected a proper "
            "rotation");
  EXPECT_EQ(r.rejected[3].format(),
            "g.npy: grasp 4: a non-finite value (NaN or infinity) in column 0 of 17");
  EXPECT_EQ(r.rejected[4].format(),
            "g.npy: grasp 5: depth -0.01 m is negative, expected the fingertips' depth beyond "
            "the grasp point (>= 0)");
  EXPECT_EQ(r.rejected[5].format(),
            "g.npy: grasp 7: a non-finite value (NaN or infinity) in column 16 of 17");
}

TEST(GraspnetImport, AWrongShapeRejectsTheFile) {
  NdArray a;
  a.shape = {2, 16};
  a.values.assign(32, 0.0);
  EXPECT_EQ(
      errorOf([&] { importGraspnetArray(a, "g.npy", Transform3D::Identity(), frankaContext()); }),
      "g.npy has shape (2, 16), expected (N, 17): score, width, height, depth, rotation "
      "(9, row-major), translation (3), object id per grasp (graspnetAPI's GraspGroup)");
}

// The Panda hand's base frame in the camera: x = (1,0,0), y = (0,0,-1), z = (0,1,0) (approach
// along the camera's y), at (0.05, 0.1, 0.4); row-major 4x4.
const std::vector<double> kHandInCamera{1, 0, 0, 0.05, 0, 0, 1, 0.1, 0, -1, 0, 0.4, 0, 0, 0, 1};

TEST(ContactGraspnetImport, OneGraspWorkedByHand) {
  // The pad centre is 0.1034 along the hand's z (build_6d_grasp's gripper_depth):
  // (0.05, 0.1 + 0.1034, 0.4) = (0.05, 0.2034, 0.4) in the camera. In the world:
  // (0.1, 0.2, 0.8) + 0.05 (1,0,0) + 0.2034 (0,-1,0) + 0.4 (0,0,-1) = (0.15, -0.0034, 0.4);
  // axes x = R_W_cam (1,0,0) = (1,0,0), y = R_W_cam (0,0,-1) = (0,0,1),
  // z = R_W_cam (0,1,0) = (0,-1,0): approach along world -y.
  NdArray grasps;
  grasps.shape = {1, 4, 4};
  grasps.values = kHandInCamera;
  NdArray scores;
  scores.shape = {1};
  scores.values = {0.7};
  const ImportResult r = importContactGraspnetArrays(grasps, scores, std::nullopt, "c.npz",
                                                     cameraLookingDown(), frankaContext());
  ASSERT_EQ(r.grasps.size(), 1u);
  const grasp::GraspRequest& g = r.grasps[0];
  EXPECT_TRANSFORM_NEAR(g.X_W_jaw, pose({1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {0.15, -0.0034, 0.4}),
                        1e-12);
  EXPECT_DOUBLE_EQ(g.width, 0.08);  // no widths: the Panda fully open
  EXPECT_DOUBLE_EQ(*g.score, 0.7);
  EXPECT_EQ(g.id, "0");
}

TEST(ContactGraspnetImport, ReadsThePlainNpzWithWidthsAndSegments) {
  test::TempDir dir;
  const auto file = dir.path() / "c.npz";
  std::vector<double> two = kHandInCamera;
  two.insert(two.end(), kHandInCamera.begin(), kHandInCamera.end());
  two[16 + 15] = 0.5;  // grasp 1's last row is 0 0 0 0.5: not a homogeneous transform
  test::writeZip(file, {{"grasps.npy", test::npyBytes("<f8", {2, 4, 4}, test::f8(two))},
                        {"scores.npy", test::npyBytes("<f4", {2}, test::f4({0.5f, 0.25f}))},
                        {"widths.npy", test::npyBytes("<f8", {2}, test::f8({0.06, 0.06}))},
                        {"segments.npy", test::npyBytes("<i8", {2}, std::string(16, '\0'))}});
  const ImportResult r = importContactGraspnet(file, cameraLookingDown(), frankaContext());
  ASSERT_EQ(r.grasps.size(), 1u);
  EXPECT_DOUBLE_EQ(r.grasps[0].width, 0.06);
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0].format(),
            file.string() +
                ": grasp 1: the transform's last row is not 0 0 0 1 (expected a 4x4 "
                "homogeneous transform)");
}

TEST(ContactGraspnetImport, RefusesPickledOutputWithTheLineThatWritesThePlainForm) {
  test::TempDir dir;
  const std::string hint =
      "np.savez(\"grasps.npz\", grasps=np.concatenate(list(pred_grasps_cam.values())), "
      "scores=np.concatenate(list(scores.values())))";
  const auto pickled = dir.path() / "predictions.npz";
  test::writeZip(pickled, {{"pred_grasps_cam.npy", test::npyBytes("|O", {}, "pickle")},
                           {"scores.npy", test::npyBytes("|O", {}, "pickle")}});
  const std::string inference =
      errorOf([&] { importContactGraspnet(pickled, Transform3D::Identity(), frankaContext()); });
  EXPECT_HAS(inference, pickled.string() + ": Contact-GraspNet's inference output");
  EXPECT_HAS(inference, hint);
  const auto objects = dir.path() / "objects.npz";
  test::writeZip(objects, {{"grasps.npy", test::npyBytes("|O", {}, "pickle")}});
  const std::string object =
      errorOf([&] { importContactGraspnet(objects, Transform3D::Identity(), frankaContext()); });
  EXPECT_HAS(object, objects.string() + ": array 'grasps': an object array");
  EXPECT_HAS(object, hint);
}

TEST(ContactGraspnetImport, MissingArraysAndWrongShapesRejectTheFile) {
  test::TempDir dir;
  const auto noScores = dir.path() / "n.npz";
  test::writeZip(noScores,
                 {{"grasps.npy", test::npyBytes("<f8", {1, 4, 4}, test::f8(kHandInCamera))}});
  EXPECT_HAS(
      errorOf([&] { importContactGraspnet(noScores, Transform3D::Identity(), frankaContext()); }),
      noScores.string() + ": no array 'scores' (member scores.npy); it has grasps");
  NdArray grasps;
  grasps.shape = {1, 4, 4};
  grasps.values = kHandInCamera;
  NdArray scores;
  scores.shape = {2};
  scores.values = {1, 1};
  EXPECT_EQ(errorOf([&] {
              importContactGraspnetArrays(grasps, scores, std::nullopt, "c.npz",
                                          Transform3D::Identity(), frankaContext());
            }),
            "c.npz: array 'scores' has shape (2,), expected (1,): one value per grasp");
  NdArray flat;
  flat.shape = {1, 16};
  flat.values = kHandInCamera;
  EXPECT_HAS(errorOf([&] {
               importContactGraspnetArrays(flat, scores, std::nullopt, "c.npz",
                                           Transform3D::Identity(), frankaContext());
             }),
             "c.npz: array 'grasps' has shape (1, 16), expected (N, 4, 4)");
  NdArray wide;
  wide.shape = {1};
  wide.values = {0.09};
  scores.shape = {1};
  scores.values = {1};
  const ImportResult r = importContactGraspnetArrays(grasps, scores, wide, "c.npz",
                                                     Transform3D::Identity(), frankaContext());
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_HAS(r.rejected[0].message, "width 0.09 m is more than hand \"franka\" opens");
}

}  // namespace
}  // namespace visgrab::importers
