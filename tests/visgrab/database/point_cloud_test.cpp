#include "visgrab/database/point_cloud.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace visgrab::database {
namespace {

PointCloud sample() {
  PointCloud cloud;
  cloud.points = {Eigen::Vector3f(0.5f, -0.25f, 1.0f), Eigen::Vector3f(-1e-3f, 2.0f, 0.75f),
                  Eigen::Vector3f(0, 0, 0)};
  cloud.colours = {{255, 0, 7}, {1, 2, 3}, {0, 0, 0}};
  cloud.comments = {"frame: rectified left camera", "second"};
  return cloud;
}

std::string errorOf(std::string_view bytes) {
  try {
    parsePointCloud(bytes, "c.ply");
  } catch (const PointCloudError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PointCloudTest, WritesTheDocumentedLayout) {
  const std::string ply = pointCloudToPly(sample());
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment frame: rectified left camera\n"
      "comment second\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  ASSERT_EQ(ply.size(), header.size() + 3 * 15);
  EXPECT_EQ(ply.substr(0, header.size()), header);
  // The second vertex, read by hand: three little-endian floats, then red, green, blue.
  const char* v = ply.data() + header.size() + 15;
  float y = 0;
  std::memcpy(&y, v + 4, 4);
  EXPECT_EQ(y, 2.0f);
  EXPECT_EQ(static_cast<unsigned char>(v[12]), 1);
  EXPECT_EQ(static_cast<unsigned char>(v[14]), 3);
}

TEST(PointCloudTest, RoundTrip) {
  const PointCloud original = sample();
  const PointCloud read = parsePointCloud(pointCloudToPly(original), "c.ply");
  EXPECT_EQ(read.points, original.points);
  EXPECT_EQ(read.colours, original.colours);
  EXPECT_EQ(read.comments, original.comments);
  EXPECT_TRUE(parsePointCloud(pointCloudToPly(PointCloud{}), "e.ply").points.empty());
}

TEST(PointCloudTest, OtherLayoutsAndTruncationNameTheLine) {
  const std::string ply = pointCloudToPly(sample());
  EXPECT_EQ(errorOf("solid x\n"),
            "c.ply: error: not a PLY file (it must start with the line \"ply\")");
  EXPECT_EQ(errorOf("ply\nformat ascii 1.0\n"),
            "c.ply:2: error: \"format ascii 1.0\": expected \"format binary_little_endian 1.0\" "
            "(the database's point cloud layout)");
  EXPECT_EQ(errorOf("ply\nformat binary_little_endian 1.0\nelement face 3\n"),
            "c.ply:3: error: \"element face 3\": expected \"element vertex N\"");
  EXPECT_EQ(errorOf("ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
                    "property double x\n"),
            "c.ply:4: error: \"property double x\": expected \"property float x\" (points are "
            "float x y z, uchar red green blue)");
  EXPECT_EQ(errorOf(ply.substr(0, 60)),
            "c.ply: error: the PLY header ends before end_header (truncated, or not a PLY file)");
  EXPECT_EQ(errorOf(ply.substr(0, ply.size() - 1)),
            "c.ply: error: the header announces 3 vertices of 15 bytes (45 bytes) but 44 bytes "
            "follow it (truncated)");
  EXPECT_EQ(errorOf(ply + "x"),
            "c.ply: error: the header announces 3 vertices of 15 bytes (45 bytes) but 46 bytes "
            "follow it");
  std::string huge = ply;
  huge.replace(huge.find("vertex 3"), 8, "vertex 99999999999999");
  EXPECT_NE(errorOf(huge).find("the header announces 99999999999999 vertices"), std::string::npos);
  EXPECT_NE(errorOf("ply\nformat binary_little_endian 1.0\nelement vertex -2\n")
                .find("expected \"element vertex N\""),
            std::string::npos);
}

TEST(PointCloudTest, WriterRejectsMismatchedColours) {
  PointCloud cloud = sample();
  cloud.colours.pop_back();
  EXPECT_THROW(pointCloudToPly(cloud), std::invalid_argument);
  cloud = sample();
  cloud.comments.push_back("two\nlines");
  EXPECT_THROW(pointCloudToPly(cloud), std::invalid_argument);
}

TEST(PointCloudTest, MissingFileIsAnError) {
  try {
    readPointCloud("/nonexistent/cloud.ply");
    FAIL();
  } catch (const PointCloudError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/cloud.ply: error: cannot open the point cloud");
  }
}

}  // namespace
}  // namespace visgrab::database
