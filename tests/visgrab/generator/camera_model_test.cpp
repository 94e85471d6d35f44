// The camera model against OpenCV as independent truth: its lens distortion against
// cv::projectPoints, the shipped calibration read with cv::FileStorage and the raw pair
// rectified with cv::cvtColor + cv::initUndistortRectifyMap + cv::remap against the shipped
// rectified pair, the raw image against ground-truth points projected with cv::projectPoints,
// and the ground-truth render against the rectified image. The ideal profile's images are
// checked against the rig's original path (a render with addSensorEffects); generation is
// checked for the same bytes with 1 and 2 threads.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <mutex>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "support/test_support.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/database/stereo_calibration.hpp"
#include "visgrab/generator/camera_model.hpp"
#include "visgrab/generator/generator.hpp"

namespace {

namespace fs = std::filesystem;
namespace db = visgrab::database;
namespace gen = visgrab::generator;

constexpr const char* kPlainJar = "plain/single/marmelade/03";
constexpr const char* kTexturedCan = "textured/single/cocacola/01";

gen::CameraProfile shippedProfile(const std::string& name) {
  return gen::loadCameraProfile(visgrab::test::sourceDir() / "scenes/cameras" / (name + ".xml"));
}

gen::GeneratorOptions optionsFor(const fs::path& out, int threads) {
  gen::GeneratorOptions options;
  options.out = out;
  options.objectSpec = visgrab::test::sourceDir() / "scenes/objects/objects.xml";
  options.handFolder = visgrab::test::sourceDir() / "scenes/hands/sdh";
  options.materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  options.seed = 11;
  options.threads = threads;
  options.camera = shippedProfile("realistic");
  return options;
}

std::vector<db::SceneConditions> testScenes() {
  return {*db::parseSceneId(kTexturedCan), *db::parseSceneId(kPlainJar)};
}

// A folder of this process's own under the test temporary folder (CTest runs each test of this
// file in a process of its own, in parallel).
fs::path uniqueDir(const std::string& name) {
  return fs::path(::testing::TempDir()) / (name + "-" + std::to_string(::getpid()));
}

// Two scenes generated once with the realistic profile, with their ground-truth renders.
struct Generated {
  fs::path dir;
  std::map<std::string, visgrab::render::RenderResult> truth;
  Generated() = default;
  Generated(Generated&&) = default;
  Generated& operator=(Generated&&) = default;
  Generated(const Generated&) = delete;
  Generated& operator=(const Generated&) = delete;
  ~Generated() {
    std::error_code ec;
    if (!dir.empty()) fs::remove_all(dir, ec);
  }
};

const Generated& generated() {
  static const Generated g = [] {
    Generated out;
    out.dir = uniqueDir("camera-model-realistic");
    fs::remove_all(out.dir);
    gen::GeneratorOptions options = optionsFor(out.dir, 2);
    std::mutex mutex;
    options.truthObserver = [&](const std::string& id, const visgrab::render::RenderResult& t) {
      const std::lock_guard lock(mutex);
      out.truth[id] = t;
    };
    const auto report = gen::generateDatabase(testScenes(), options);
    if (!report.failures.empty()) throw std::runtime_error(report.failures.front());
    return out;
  }();
  return g;
}

fs::path sceneFile(const std::string& id, const std::string& name) {
  return generated().dir / "scenes" / id / name;
}

cv::Mat readMatrix(const cv::FileStorage& fs, const char* name) {
  cv::Mat m;
  fs[name] >> m;
  return m;
}

// Red pixels (the jar's body) of a BGR image.
cv::Mat redMask(const cv::Mat& bgr) {
  cv::Mat mask(bgr.size(), CV_8U, cv::Scalar(0));
  for (int r = 0; r < bgr.rows; ++r) {
    for (int c = 0; c < bgr.cols; ++c) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(r, c);
      mask.at<std::uint8_t>(r, c) = p[2] > 90 && p[2] > p[1] + 60 && p[2] > p[0] + 60 ? 255 : 0;
    }
  }
  return mask;
}

// The affine map moving an image by (dx, dy) pixels.
cv::Mat shift(double dx, double dy) {
  cv::Mat m = cv::Mat::eye(2, 3, CV_64F);
  m.at<double>(0, 2) = dx;
  m.at<double>(1, 2) = dy;
  return m;
}

// Where `mask` (the red body) sits between the left and right silhouette edges of `region`
// (the object), over the rows where both have pixels: the median of (left inset - right inset) /
// 2, in pixels. 0 when the body is centred in the silhouette (the detected body may be narrower
// than the silhouette, its shaded rims being dark, but evenly so); a shift of the silhouette by
// d pixels moves it by d.
double medianCentreOffset(const cv::Mat& mask, const cv::Mat& region) {
  std::vector<double> offsets;
  for (int r = 0; r < mask.rows; ++r) {
    int m0 = -1, m1 = -1, g0 = -1, g1 = -1;
    for (int c = 0; c < mask.cols; ++c) {
      if (mask.at<std::uint8_t>(r, c) != 0) {
        if (m0 < 0) m0 = c;
        m1 = c;
      }
      if (region.at<std::uint8_t>(r, c) != 0) {
        if (g0 < 0) g0 = c;
        g1 = c;
      }
    }
    if (m0 < 0 || g0 < 0) continue;
    offsets.push_back(0.5 * ((m0 - g0) - (g1 - m1)));
  }
  if (offsets.empty()) return 1e9;
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  return offsets[offsets.size() / 2];
}

// Fraction of `mask`'s pixels inside `region` grown by one pixel.
double fractionInside(const cv::Mat& mask, const cv::Mat& region) {
  cv::Mat grown;
  cv::dilate(region, grown, cv::Mat::ones(3, 3, CV_8U));
  const int all = cv::countNonZero(mask);
  cv::Mat inside;
  cv::bitwise_and(mask, grown, inside);
  return all > 0 ? static_cast<double>(cv::countNonZero(inside)) / all : 0.0;
}

TEST(CameraModel, DistortionIsOpenCvsModelAndUndistortionItsInverse) {
  const std::array<double, 5> d{-0.22, 0.09, 0.0006, -0.0004, -0.015};
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  const cv::Mat D = (cv::Mat_<double>(1, 5) << d[0], d[1], d[2], d[3], d[4]);
  std::vector<cv::Point3d> points;
  for (double x = -0.5; x <= 0.5; x += 0.1) {
    for (double y = -0.4; y <= 0.4; y += 0.1) points.emplace_back(x, y, 1.0);
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, projected);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d xy(points[i].x, points[i].y);
    const Eigen::Vector2d xd = gen::distortPoint(xy, d);
    EXPECT_NEAR(xd.x(), projected[i].x, 1e-12);
    EXPECT_NEAR(xd.y(), projected[i].y, 1e-12);
    const Eigen::Vector2d back = gen::undistortPoint(xd, d);
    EXPECT_NEAR(back.x(), xy.x(), 1e-10);
    EXPECT_NEAR(back.y(), xy.y(), 1e-10);
  }
}

// The ideal profile renders 1:1 and applies exactly what the rig always applied
// (addSensorEffects: blur on the 8-bit image, then per-byte Gaussian noise from the same
// stream), so its rectified images are the database's images as before the camera model. This
// fails if the ideal path resamples, reorders the noise or changes the calibration.
TEST(CameraModel, TheIdealProfileIsTheOriginalRigPath) {
  const gen::CameraRig rig(shippedProfile("ideal"));
  const auto original = gen::rigCalibration(gen::StereoRigSpec{});
  EXPECT_EQ(rig.calibration().P1, original.P1);
  EXPECT_EQ(rig.calibration().P2, original.P2);
  EXPECT_EQ(rig.calibration().Q, original.Q);
  EXPECT_TRUE(rig.calibration().X_TL.isApprox(original.X_TL, 0.0));
  const auto [left, right] = gen::rigCameras(original);
  for (int side = 0; side < 2; ++side) {
    const auto& camera = side == 0 ? left : right;
    EXPECT_EQ(rig.renderCamera(side).width, camera.width);
    EXPECT_EQ(rig.renderCamera(side).cx, camera.cx);
    EXPECT_TRUE(rig.renderCamera(side).X_WC.isApprox(camera.X_WC, 0.0));
    visgrab::visual::RgbImage render;
    render.width = camera.width;
    render.height = camera.height;
    gen::Random pixels(side + 1);
    for (int i = 0; i < render.width * render.height * 3; ++i) {
      render.pixels.push_back(static_cast<std::uint8_t>(pixels.next() % 256));
    }
    gen::Random a(5, "scene|left.png");
    const cv::Mat rectified = rig.rectify(side, rig.rawImage(side, render, a));
    visgrab::visual::RgbImage expected = render;
    gen::Random b(5, "scene|left.png");
    gen::addSensorEffects(expected, gen::StereoRigSpec{}, b);
    cv::Mat expectedBgr;
    cv::cvtColor(cv::Mat(expected.height, expected.width, CV_8UC3, expected.pixels.data()),
                 expectedBgr, cv::COLOR_RGB2BGR);
    ASSERT_EQ(rectified.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(rectified, expectedBgr, cv::NORM_INF), 0.0) << "side " << side;
  }
}

TEST(CameraModel, TheCalibrationReadsWithOpenCvAndPassesTheChecks) {
  const fs::path file = sceneFile(kPlainJar, "calibration.yml");
  EXPECT_NO_THROW(db::readCalibration(file));
  const cv::FileStorage fs(file.string(), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  const cv::Mat K1 = readMatrix(fs, "K1");
  const cv::Mat D1 = readMatrix(fs, "D1");
  const cv::Mat R = readMatrix(fs, "R");
  const cv::Mat T = readMatrix(fs, "T");
  ASSERT_EQ(D1.total(), 5u);
  EXPECT_NEAR(D1.at<double>(0), -0.22, 1e-12);
  // R1, P1 as OpenCV computes them from the raw calibration.
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(K1, D1, readMatrix(fs, "K2"), readMatrix(fs, "D2"), cv::Size(720, 540), R, T,
                    R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0.0);
  EXPECT_LT(cv::norm(R1, readMatrix(fs, "R1"), cv::NORM_INF), 1e-12);
  EXPECT_LT(cv::norm(P2, readMatrix(fs, "P2"), cv::NORM_INF), 1e-9);
  EXPECT_LT(cv::norm(Q, readMatrix(fs, "Q"), cv::NORM_INF), 1e-9);
}

double psnrAwayFromHighlights(const cv::Mat& a, const cv::Mat& b) {
  double sum = 0.0;
  long count = 0;
  for (int r = 0; r < a.rows; ++r) {
    for (int c = 0; c < a.cols; ++c) {
      const cv::Vec3b p = a.at<cv::Vec3b>(r, c);
      const cv::Vec3b q = b.at<cv::Vec3b>(r, c);
      if (std::max({p[0], p[1], p[2], q[0], q[1], q[2]}) >= 250) continue;
      for (int k = 0; k < 3; ++k) sum += (p[k] - q[k]) * (p[k] - q[k]);
      count += 3;
    }
  }
  return 10.0 * std::log10(255.0 * 255.0 / std::max(sum / static_cast<double>(count), 1e-12));
}

// A user's rectification with OpenCV alone reproduces the shipped rectified pair.
TEST(CameraModel, OpenCvRectifiesTheRawPairIntoTheShippedPair) {
  for (const char* id : {kTexturedCan, kPlainJar}) {
    const cv::FileStorage fs(sceneFile(id, "calibration.yml").string(), cv::FileStorage::READ);
    for (int side = 0; side < 2; ++side) {
      const std::string s = side == 0 ? "1" : "2";
      const cv::Mat raw =
          cv::imread(sceneFile(id, side == 0 ? "raw_left.png" : "raw_right.png").string(),
                     cv::IMREAD_UNCHANGED);
      ASSERT_EQ(raw.type(), CV_8UC1) << "the raw images are single-channel RGGB mosaics";
      cv::Mat colour;
      cv::cvtColor(raw, colour, cv::COLOR_BayerBG2BGR);
      cv::Mat map1, map2, rectified;
      cv::initUndistortRectifyMap(
          readMatrix(fs, ("K" + s).c_str()), readMatrix(fs, ("D" + s).c_str()),
          readMatrix(fs, ("R" + s).c_str()), readMatrix(fs, ("P" + s).c_str()), raw.size(),
          CV_32FC1, map1, map2);
      // alpha 0: every rectified pixel samples inside the raw image.
      double lo = 0, hi = 0;
      cv::minMaxLoc(map1, &lo, &hi);
      EXPECT_GE(lo, -0.5);
      EXPECT_LE(hi, raw.cols - 0.5);
      cv::minMaxLoc(map2, &lo, &hi);
      EXPECT_GE(lo, -0.5);
      EXPECT_LE(hi, raw.rows - 0.5);
      cv::remap(colour, rectified, map1, map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
      const cv::Mat shipped =
          cv::imread(sceneFile(id, side == 0 ? "left.png" : "right.png").string());
      const double psnr = psnrAwayFromHighlights(rectified, shipped);
      std::cout << id << " side " << side << ": PSNR " << psnr << " dB, largest difference "
                << cv::norm(rectified, shipped, cv::NORM_INF) << " grey levels\n";
      EXPECT_GE(psnr, 30.0) << id << " side " << side;
    }
  }
}

// The ground truth of the rectified left view lies where the rectified image shows the object:
// the jar's red body falls inside the rendered object mask (grown by one pixel).
TEST(CameraModel, TheGroundTruthRenderAgreesWithTheRectifiedImage) {
  const auto& truth = generated().truth.at(kPlainJar);
  cv::Mat objects(truth.instanceIds.height, truth.instanceIds.width, CV_8U, cv::Scalar(0));
  for (int r = 0; r < objects.rows; ++r) {
    for (int c = 0; c < objects.cols; ++c) {
      if (truth.instanceIds.at(r, c) >= 10) objects.at<std::uint8_t>(r, c) = 255;
    }
  }
  const cv::Mat red = redMask(cv::imread(sceneFile(kPlainJar, "left.png").string()));
  ASSERT_GT(cv::countNonZero(red), 1500);
  EXPECT_GT(fractionInside(red, objects), 0.98);
  EXPECT_LE(std::abs(medianCentreOffset(red, objects)), 1.0);
  // Three pixels off, the check fails: it sees the silhouette.
  cv::Mat shifted;
  cv::warpAffine(objects, shifted, shift(3, 0), objects.size());
  EXPECT_GE(std::abs(medianCentreOffset(red, shifted)), 2.0);
}

// Ground-truth points of the jar (the rectified view's depth, turned back into the raw left
// camera) projected with cv::projectPoints and the raw calibration land on the jar in the raw
// image.
TEST(CameraModel, TheRawImageShowsPointsWhereProjectPointsPutsThem) {
  const auto& truth = generated().truth.at(kPlainJar);
  const auto calibration = db::readCalibration(sceneFile(kPlainJar, "calibration.yml"));
  std::vector<cv::Point3d> points;
  const double f = calibration.P1(0, 0);
  for (int r = 0; r < truth.depth.height; ++r) {
    for (int c = 0; c < truth.depth.width; ++c) {
      if (truth.instanceIds.at(r, c) < 10) continue;
      const double z = truth.depth.at(r, c);
      const Eigen::Vector3d rectified((c - calibration.P1(0, 2)) / f * z,
                                      (r - calibration.P1(1, 2)) / f * z, z);
      const Eigen::Vector3d raw = calibration.R1.transpose() * rectified;
      points.emplace_back(raw.x(), raw.y(), raw.z());
    }
  }
  cv::Mat K(3, 3, CV_64F);
  cv::Mat D(1, 5, CV_64F);
  for (int i = 0; i < 9; ++i) K.at<double>(i / 3, i % 3) = calibration.K1(i / 3, i % 3);
  for (int i = 0; i < 5; ++i) D.at<double>(i) = calibration.D1(i);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, pixels);
  cv::Mat expected(calibration.height, calibration.width, CV_8U, cv::Scalar(0));
  for (const auto& p : pixels) {
    const int c = static_cast<int>(std::lround(p.x));
    const int r = static_cast<int>(std::lround(p.y));
    if (r >= 0 && r < expected.rows && c >= 0 && c < expected.cols) {
      expected.at<std::uint8_t>(r, c) = 255;
    }
  }
  cv::morphologyEx(expected, expected, cv::MORPH_CLOSE, cv::Mat::ones(3, 3, CV_8U));
  cv::Mat colour;
  cv::cvtColor(cv::imread(sceneFile(kPlainJar, "raw_left.png").string(), cv::IMREAD_UNCHANGED),
               colour, cv::COLOR_BayerBG2BGR);
  const cv::Mat red = redMask(colour);
  ASSERT_GT(cv::countNonZero(red), 1500);
  EXPECT_GT(fractionInside(red, expected), 0.97);
  EXPECT_LE(std::abs(medianCentreOffset(red, expected)), 1.0);
  cv::Mat shifted;
  cv::warpAffine(expected, shifted, shift(3, 0), expected.size());
  EXPECT_GE(std::abs(medianCentreOffset(red, shifted)), 2.0);
}

std::string bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(CameraModel, SameBytesWithOneAndTwoThreads) {
  const fs::path one = uniqueDir("camera-model-one-thread");
  fs::remove_all(one);
  ASSERT_TRUE(gen::generateDatabase(testScenes(), optionsFor(one, 1)).failures.empty());
  int compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(one / "scenes")) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), one);
    EXPECT_EQ(bytes(entry.path()), bytes(generated().dir / relative)) << relative;
    ++compared;
  }
  // Per scene: the raw and rectified pairs, calibration, scene files, disparity, point cloud,
  // depth, mask and poses.
  EXPECT_EQ(compared, 2 * 12);
  fs::remove_all(one);
}

}  // namespace
