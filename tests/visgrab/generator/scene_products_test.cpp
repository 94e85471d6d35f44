// The files beside a generated scene's images (disparity.png, cloud.ply, depth.png, mask.png,
// poses.yml) in the shared test database, checked with independent readers (cv::imread, a PLY
// parser written here, cv::FileStorage) against independent truth: a render of the rectified
// left view from the database's own object files and ground-truth poses, the calibration's P1
// and P2, and the index.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "support/test_database.hpp"
#include "support/test_support.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/generator/scene_products.hpp"
#include "visgrab/render/mesh_loader.hpp"
#include "visgrab/render/offscreen_renderer.hpp"

namespace {

namespace fs = std::filesystem;
namespace db = visgrab::database;
namespace gen = visgrab::generator;
using rw::math::Transform3D;

// The rectified left camera's pose in the table frame, from the calibration's definitions.
Transform3D rectifiedLeft(const db::StereoCalibration& k) {
  Transform3D X = k.X_TL;
  X.linear() = k.X_TL.linear() * k.R1.transpose();
  return X;
}

// The truth of the rectified left view from the database's own files
// (test/support/test_database.hpp): depth and instance ids (table 1, objects 10 + id).
visgrab::render::RenderResult renderTruth(const db::Database& database,
                                          const db::SceneEntry& entry) {
  return visgrab::test::renderLeftViewTruth(database, entry);
}

struct PlyPoint {
  float x, y, z;
  std::uint8_t r, g, b;
};

// A PLY reader of its own: the header word by word, then the binary little-endian records.
std::vector<PlyPoint> readPly(const fs::path& file, std::vector<std::string>& comments) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "ply") << file;
  std::size_t count = 0;
  std::vector<std::string> properties;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      std::string format;
      words >> format;
      EXPECT_EQ(format, "binary_little_endian") << file;
    } else if (word == "comment") {
      comments.push_back(line.substr(8));
    } else if (word == "element") {
      std::string name;
      words >> name >> count;
      EXPECT_EQ(name, "vertex") << file;
    } else if (word == "property") {
      std::string type, name;
      words >> type >> name;
      properties.push_back(type + " " + name);
    }
  }
  EXPECT_EQ(properties, (std::vector<std::string>{"float x", "float y", "float z", "uchar red",
                                                  "uchar green", "uchar blue"}))
      << file;
  std::vector<PlyPoint> points(count);
  for (PlyPoint& p : points) {
    char record[15];
    in.read(record, sizeof record);
    std::memcpy(&p.x, record, 4);
    std::memcpy(&p.y, record + 4, 4);
    std::memcpy(&p.z, record + 8, 4);
    p.r = static_cast<std::uint8_t>(record[12]);
    p.g = static_cast<std::uint8_t>(record[13]);
    p.b = static_cast<std::uint8_t>(record[14]);
  }
  EXPECT_TRUE(in) << file << ": fewer bytes than the header announces";
  EXPECT_EQ(in.peek(), std::char_traits<char>::eof()) << file << ": bytes after the vertices";
  return points;
}

Eigen::Matrix4d matrixNode(const cv::FileNode& node) {
  cv::Mat m;
  node >> m;
  EXPECT_EQ(m.rows, 4);
  EXPECT_EQ(m.cols, 4);
  Eigen::Matrix4d out = Eigen::Matrix4d::Zero();
  for (int r = 0; r < 4 && r < m.rows; ++r) {
    for (int c = 0; c < 4 && c < m.cols; ++c) out(r, c) = m.at<double>(r, c);
  }
  return out;
}

TEST(SceneProducts, EveryFileOpensWithOpenCVWithTheDocumentedTypes) {
  const auto& database = visgrab::test::testDatabase();
  for (const auto& entry : database.list()) {
    const auto k = database.calibration(entry.id);
    const cv::Size size(k.width, k.height);
    const cv::Mat disparity = cv::imread(entry.disparity.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat depth = cv::imread(entry.depth.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat mask = cv::imread(entry.mask.string(), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(disparity.type(), CV_16UC1) << entry.id;
    EXPECT_EQ(depth.type(), CV_16UC1) << entry.id;
    EXPECT_EQ(mask.type(), CV_8UC1) << entry.id;
    EXPECT_EQ(disparity.size(), size) << entry.id;
    EXPECT_EQ(depth.size(), size) << entry.id;
    EXPECT_EQ(mask.size(), size) << entry.id;
    // The Database's reader gives the same disparities (value / 256, -1 where 0).
    const cv::Mat read = database.disparityImage(entry.id);
    int known = 0;
    for (int r = 0; r < size.height; ++r) {
      for (int c = 0; c < size.width; ++c) {
        const std::uint16_t v = disparity.at<std::uint16_t>(r, c);
        if (v == 0) {
          ASSERT_LT(read.at<float>(r, c), 0.0f);
        } else {
          ++known;
          ASSERT_EQ(read.at<float>(r, c), v / 256.0f);
        }
      }
    }
    EXPECT_GT(known, size.area() / 4) << entry.id;  // the plain table leaves most holes
    cv::FileStorage poses(entry.poses.string(), cv::FileStorage::READ);
    ASSERT_TRUE(poses.isOpened()) << entry.poses;
    EXPECT_EQ(poses["objects"].size(), entry.groundTruth.size()) << entry.id;
    std::vector<std::string> comments;
    EXPECT_FALSE(readPly(entry.pointCloud, comments).empty()) << entry.id;
  }
}

TEST(SceneProducts, DepthAndMaskEqualTheRenderedTruth) {
  const auto& database = visgrab::test::testDatabase();
  for (const auto& entry : database.list()) {
    const auto truth = renderTruth(database, entry);
    const cv::Mat depth = cv::imread(entry.depth.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat mask = cv::imread(entry.mask.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth.type(), CV_16UC1);
    ASSERT_EQ(mask.type(), CV_8UC1);
    int depthOff = 0, maskOff = 0, maskEdge = 0, objectPixels = 0;
    double worst = 0.0;
    for (int r = 0; r < truth.depth.height; ++r) {
      for (int c = 0; c < truth.depth.width; ++c) {
        const float z = truth.depth.at(r, c);
        const std::uint16_t stored = depth.at<std::uint16_t>(r, c);
        if (std::isfinite(z)) {
          const double error = std::abs(stored * 1e-4 - z);
          worst = std::max(worst, error);
          // Half the 0.1 mm unit, plus 1 um for the object files' rounded vertices.
          if (error > 0.5e-4 + 1e-6) ++depthOff;
        } else if (stored != 0) {
          ++depthOff;
        }
        const std::uint16_t id = truth.instanceIds.at(r, c);
        const int expected = id == 0 ? 0 : id == 1 ? 255 : id - 10;
        if (id >= 10) ++objectPixels;
        const int stored8 = mask.at<std::uint8_t>(r, c);
        if (stored8 != expected) {
          // This render reads the object files, whose vertices are rounded to 1 um: a pixel
          // centre that close to a silhouette may land on the other side. Such a pixel is on
          // the edge between the two ids (the stored one is a neighbour's); anything else fails.
          bool edge = false;
          for (int dr = -1; dr <= 1; ++dr) {
            for (int dc = -1; dc <= 1; ++dc) {
              const int rr = std::clamp(r + dr, 0, truth.depth.height - 1);
              const int cc = std::clamp(c + dc, 0, truth.depth.width - 1);
              const std::uint16_t n = truth.instanceIds.at(rr, cc);
              edge = edge || (n == 0 ? 0 : n == 1 ? 255 : n - 10) == stored8;
            }
          }
          ++(edge ? maskEdge : maskOff);
        }
      }
    }
    EXPECT_GT(objectPixels, 2000) << entry.id;
    EXPECT_EQ(depthOff, 0) << entry.id << " worst " << worst;
    EXPECT_EQ(maskOff, 0) << entry.id;
    EXPECT_LE(maskEdge, 3) << entry.id << ": silhouette pixels on the other side";
  }
}

TEST(SceneProducts, PointCloudPointsLieOnTheRenderedSurfaces) {
  const auto& database = visgrab::test::testDatabase();
  for (const auto& entry : database.list()) {
    const auto k = database.calibration(entry.id);
    const cv::Mat depth = cv::imread(entry.depth.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat mask = cv::imread(entry.mask.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat disparity = cv::imread(entry.disparity.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat left = cv::imread(entry.leftImage.string(), cv::IMREAD_COLOR);
    std::vector<std::string> comments;
    const std::vector<PlyPoint> points = readPly(entry.pointCloud, comments);
    std::vector<double> objectErrors;
    int reprojectionOff = 0, colourOff = 0;
    for (const PlyPoint& p : points) {
      const Eigen::Vector4d h(p.x, p.y, p.z, 1.0);
      const Eigen::Vector3d u1 = k.P1 * h;
      const Eigen::Vector3d u2 = k.P2 * h;
      const double u = u1.x() / u1.z(), v = u1.y() / u1.z();
      const int c = static_cast<int>(std::lround(u)), r = static_cast<int>(std::lround(v));
      ASSERT_TRUE(c >= 0 && r >= 0 && c < k.width && r < k.height) << entry.id;
      // The point is the stored disparity of its pixel reprojected: it projects back onto that
      // pixel, with that disparity between the views.
      const double d = disparity.at<std::uint16_t>(r, c) / 256.0;
      if (std::abs(u - c) > 1e-3 || std::abs(v - r) > 1e-3 ||
          std::abs(u - u2.x() / u2.z() - d) > 1e-3) {
        ++reprojectionOff;
      }
      const cv::Vec3b bgr = left.at<cv::Vec3b>(r, c);
      if (bgr != cv::Vec3b(p.b, p.g, p.r)) ++colourOff;
      const std::uint8_t id = mask.at<std::uint8_t>(r, c);
      if (id == 0 || id == 255) continue;
      objectErrors.push_back(std::abs(p.z - depth.at<std::uint16_t>(r, c) * 1e-4));
    }
    EXPECT_EQ(reprojectionOff, 0) << entry.id;
    EXPECT_EQ(colourOff, 0) << entry.id;
    ASSERT_GT(objectErrors.size(), 200u) << entry.id;
    std::nth_element(objectErrors.begin(), objectErrors.begin() + objectErrors.size() / 2,
                     objectErrors.end());
    const double median = objectErrors[objectErrors.size() / 2];
    std::cout << entry.id << ": " << points.size() << " points, " << objectErrors.size()
              << " on objects, median depth error " << median * 1000.0 << " mm\n";
    EXPECT_LT(median, 0.003) << entry.id;
    // The header names the frame and its pose in the table frame.
    ASSERT_EQ(comments.size(), 4u);
    EXPECT_NE(comments[0].find("rectified left camera frame"), std::string::npos);
    std::istringstream pose(comments[3].substr(comments[3].find(": ") + 2));
    Eigen::Matrix4d X = Eigen::Matrix4d::Zero();
    for (int i = 0; i < 16; ++i) pose >> X(i / 4, i % 4);
    EXPECT_TRUE(X.isApprox(rectifiedLeft(k).matrix(), 1e-8)) << X;
  }
}

TEST(SceneProducts, PosesAgreeWithTheIndexAndTheCalibration) {
  const auto& database = visgrab::test::testDatabase();
  for (const auto& entry : database.list()) {
    const auto k = database.calibration(entry.id);
    cv::FileStorage poses(entry.poses.string(), cv::FileStorage::READ);
    ASSERT_TRUE(poses.isOpened()) << entry.poses;
    const Eigen::Matrix4d X_TC = matrixNode(poses["X_table_camera"]);
    EXPECT_TRUE(X_TC.isApprox(rectifiedLeft(k).matrix(), 1e-12)) << entry.id;
    const cv::FileNode objects = poses["objects"];
    ASSERT_EQ(objects.size(), entry.groundTruth.size());
    for (std::size_t i = 0; i < entry.groundTruth.size(); ++i) {
      const cv::FileNode o = objects[static_cast<int>(i)];
      EXPECT_EQ(static_cast<int>(o["id"]), entry.groundTruth[i].object);
      EXPECT_EQ(static_cast<std::string>(o["name"]),
                std::string(db::objectName(entry.groundTruth[i].object)));
      const Eigen::Matrix4d X_TO = matrixNode(o["X_table_object"]);
      // The index holds poses at 1 nm and 1e-9 degree.
      EXPECT_LT((X_TO - entry.groundTruth[i].X_WO.matrix()).cwiseAbs().maxCoeff(), 1e-8);
      const Eigen::Matrix4d X_CO = matrixNode(o["X_camera_object"]);
      EXPECT_LT((X_TC * X_CO - X_TO).cwiseAbs().maxCoeff(), 1e-12) << entry.id;
    }
  }
}

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SceneProducts, AResumedGenerationRemakesAMissingProductIdentically) {
  visgrab::test::TempDir tmp;
  gen::GeneratorOptions options;
  options.out = tmp.path() / "db";
  options.objectSpec = visgrab::test::sourceDir() / "scenes/objects/objects.xml";
  options.handFolder = visgrab::test::sourceDir() / "scenes/hands/sdh";
  options.materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  options.seed = 9;
  const std::vector<db::SceneConditions> scenes{
      db::SceneConditions::single(db::Texture::kTextured, 11, 1)};
  ASSERT_EQ(gen::generateDatabase(scenes, options).generated, 1);
  const fs::path folder = options.out / "scenes" / db::sceneIdOf(scenes[0]);
  std::map<std::string, std::string> before;
  for (const char* name : {"disparity.png", "cloud.ply", "depth.png", "mask.png", "poses.yml"}) {
    before[name] = bytesOf(folder / name);
    EXPECT_FALSE(before[name].empty()) << name;
  }
  // The index of format 2 names the five files; the ideal rig's raw pair is its rectified pair.
  const std::string index = bytesOf(options.out / "index.xml");
  EXPECT_NE(index.find("formatVersion=\"2\""), std::string::npos);
  EXPECT_NE(index.find("pointCloud=\"scenes/textured/single/peachcan/01/cloud.ply\""),
            std::string::npos)
      << index;
  EXPECT_NE(index.find("rawLeft=\"scenes/textured/single/peachcan/01/left.png\""),
            std::string::npos)
      << index;
  // A lost point cloud makes the scene incomplete; the next run makes it again, the same.
  fs::remove(folder / "cloud.ply");
  const auto resumed = gen::generateDatabase(scenes, options);
  EXPECT_EQ(resumed.generated, 1);
  for (const auto& [name, bytes] : before) EXPECT_EQ(bytesOf(folder / name), bytes) << name;
  EXPECT_EQ(gen::generateDatabase(scenes, options).skipped, 1);
}

TEST(SceneProducts, EncodersFollowTheDocumentedScales) {
  cv::Mat disparity(1, 4, CV_32FC1);
  disparity.at<float>(0, 0) = 40.0625f;
  disparity.at<float>(0, 1) = -1.0f;
  disparity.at<float>(0, 2) = std::numeric_limits<float>::quiet_NaN();
  disparity.at<float>(0, 3) = 256.0f;  // beyond 65535 / 256: none
  const cv::Mat d = gen::encodeDisparity(disparity);
  EXPECT_EQ(d.at<std::uint16_t>(0, 0), 10256);
  EXPECT_EQ(d.at<std::uint16_t>(0, 1), 0);
  EXPECT_EQ(d.at<std::uint16_t>(0, 2), 0);
  EXPECT_EQ(d.at<std::uint16_t>(0, 3), 0);
  visgrab::render::DepthImage depth{3, 1, {0.65432f, std::numeric_limits<float>::infinity(), 7.0f}};
  const cv::Mat z = gen::encodeDepth(depth);
  EXPECT_EQ(z.at<std::uint16_t>(0, 0), 6543);
  EXPECT_EQ(z.at<std::uint16_t>(0, 1), 0);
  EXPECT_EQ(z.at<std::uint16_t>(0, 2), 0);  // beyond 6.5535 m
  visgrab::render::InstanceIdImage ids{4, 1, {0, 1, 15, 24}};
  const std::vector<gen::TruthObject> objects = {{5, "cocacola", 15, Transform3D::Identity()},
                                                 {14, "saltcylinder", 24, Transform3D::Identity()}};
  const cv::Mat mask = gen::encodeInstanceMask(ids, 1, objects);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 1), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 2), 5);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 3), 14);
  ids.values[3] = 99;
  try {
    gen::encodeInstanceMask(ids, 1, objects);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "scene products: instance id 99 at pixel (3, 0) is neither the table's nor an "
              "object's");
  }
}

}  // namespace
