#include "visgrab/database/stereo_calibration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "rw/math/rpy.hpp"
#include "support/test_support.hpp"

namespace visgrab::database {
namespace {

const rw::math::Transform3D kPose =
    rw::math::rpyTransform(Eigen::Vector3d(0.1, 2.6, -1.7), Eigen::Vector3d(0.05, -0.6, 0.7));

StereoCalibration sampleRig() {
  return idealRectifiedRig(525.3, 524.1, 319.7, 241.3, 0.12, 640, 480, kPose);
}

template <int R, int C>
void expectMatNear(const cv::Mat& cvMat, const Eigen::Matrix<double, R, C>& m, double tol,
                   const char* name) {
  ASSERT_EQ(cvMat.rows, R) << name;
  ASSERT_EQ(cvMat.cols, C) << name;
  for (int r = 0; r < R; ++r) {
    for (int c = 0; c < C; ++c) {
      EXPECT_NEAR(cvMat.at<double>(r, c), m(r, c), tol) << name << "(" << r << "," << c << ")";
    }
  }
}

TEST(StereoCalibrationTest, IdealRigMatchesStereoRectify) {
  struct Case {
    double fx, fy, cx, cy, b;
    int w, h;
  };
  for (const Case& k : {Case{525.3, 524.1, 319.7, 241.3, 0.12, 640, 480},
                        Case{1000, 1000, 639.5, 479.5, 0.075, 1280, 960},
                        Case{811.37, 809.9, 402.123, 297.77, 0.2, 800, 600},
                        Case{300.1, 301.7, 150.3, 121.9, 0.05, 321, 243}}) {
    const StereoCalibration rig = idealRectifiedRig(k.fx, k.fy, k.cx, k.cy, k.b, k.w, k.h, kPose);
    const cv::Matx33d K(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
    const cv::Mat D = cv::Mat::zeros(1, 5, CV_64F);
    cv::Mat R1, R2, P1, P2, Q;
    cv::stereoRectify(K, D, K, D, cv::Size(k.w, k.h), cv::Matx33d::eye(), cv::Vec3d(-k.b, 0, 0), R1,
                      R2, P1, P2, Q);
    expectMatNear<3, 3>(R1, rig.R1, 1e-9, "R1");
    expectMatNear<3, 3>(R2, rig.R2, 1e-9, "R2");
    expectMatNear<3, 4>(P1, rig.P1, 1e-9, "P1");
    expectMatNear<3, 4>(P2, rig.P2, 1e-9, "P2");
    expectMatNear<4, 4>(Q, rig.Q, 1e-9, "Q");
    EXPECT_EQ(rig.check(), "");
    EXPECT_NEAR(rig.baseline(), k.b, 1e-12);
  }
  EXPECT_THROW(idealRectifiedRig(0, 500, 320, 240, 0.1, 640, 480, kPose), std::invalid_argument);
  EXPECT_THROW(idealRectifiedRig(500, 500, 320, 240, -0.1, 640, 480, kPose), std::invalid_argument);
}

TEST(StereoCalibrationTest, YamlRoundTripIsExact) {
  StereoCalibration rig = sampleRig();
  rig.D1 << 0.01, -0.002, 0.0001, 0.0003, 1e-5;
  const std::string yaml = calibrationToYaml(rig);
  EXPECT_NE(yaml.find("X_table_left"), std::string::npos);
  EXPECT_NE(yaml.find("image_size"), std::string::npos);
  const StereoCalibration read = parseCalibration(yaml, "c.yml");
  EXPECT_EQ(read.width, 640);
  EXPECT_EQ(read.height, 480);
  EXPECT_EQ(read.K1, rig.K1);
  EXPECT_EQ(read.D1, rig.D1);
  EXPECT_EQ(read.K2, rig.K2);
  EXPECT_EQ(read.D2, rig.D2);
  EXPECT_EQ(read.R, rig.R);
  EXPECT_EQ(read.T, rig.T);
  EXPECT_EQ(read.P1, rig.P1);
  EXPECT_EQ(read.P2, rig.P2);
  EXPECT_EQ(read.Q, rig.Q);
  EXPECT_EQ(read.X_TL.matrix(), rig.X_TL.matrix());

  test::TempDir dir;
  writeCalibration(dir.path() / "sub" / "calibration.yml", rig);
  EXPECT_EQ(readCalibration(dir.path() / "sub" / "calibration.yml").P2, rig.P2);
  // OpenCV itself reads the file.
  cv::FileStorage fs((dir.path() / "sub" / "calibration.yml").string(), cv::FileStorage::READ);
  cv::Mat P2;
  fs["P2"] >> P2;
  EXPECT_EQ(P2.at<double>(0, 3), rig.P2(0, 3));
}

std::string errorOf(const std::string& yaml) {
  try {
    parseCalibration(yaml, "scene/calibration.yml");
  } catch (const CalibrationError& e) {
    return e.what();
  }
  return "no error";
}

// The sample rig's YAML with node `node` replaced by `replacement` (whole node text).
std::string withNode(const std::string& node, const std::string& replacement) {
  const std::string yaml = calibrationToYaml(sampleRig());
  const std::regex pattern(node + R"(: !!opencv-matrix[\s\S]*?\]\n)");
  std::string out =
      std::regex_replace(yaml, pattern, replacement, std::regex_constants::format_first_only);
  EXPECT_NE(out, yaml) << "node " << node << " not found";
  return out;
}

std::string matrix(const std::string& name, int rows, int cols, const std::string& data) {
  return name + ": !!opencv-matrix\n   rows: " + std::to_string(rows) +
         "\n   cols: " + std::to_string(cols) + "\n   dt: d\n   data: [ " + data + " ]\n";
}

// "scene/calibration.yml:N" with N the 1-based line of `yaml` that starts with `start`.
std::string at(const std::string& yaml, const std::string& start) {
  const std::size_t pos = yaml.rfind('\n' + start) + 1;
  EXPECT_NE(pos, 0U) << start;
  return "scene/calibration.yml:" +
         std::to_string(1 + std::count(yaml.begin(), yaml.begin() + static_cast<long>(pos), '\n'));
}

TEST(StereoCalibrationTest, MalformedFilesNameFileLineAndNode) {
  EXPECT_EQ(errorOf(""), "scene/calibration.yml: error: the file is empty");
  EXPECT_EQ(errorOf("K1: [ 1, 2\nfoo: }"),
            "scene/calibration.yml:1: error: not a valid OpenCV YAML file: '[' is not closed "
            "(expected ']')");
  EXPECT_EQ(errorOf(withNode("P2", "")), "scene/calibration.yml: error: missing node \"P2\"");
  std::string y = withNode("K1", matrix("K1", 3, 4, "1,0,0,0,0,1,0,0,0,0,1,0"));
  EXPECT_EQ(errorOf(y), at(y, "K1:") + ": error: node \"K1\": expected a 3x3 matrix, got 3x4");
  y = withNode("R", matrix("R", 3, 3, "1,0,0,0,1,0,0,0"));
  EXPECT_EQ(errorOf(y), at(y, "   data: [ 1,0,0,0,1,0,0,0 ]") +
                            ": error: node \"R\": data must hold rows x cols = 9 numbers, got 8");
  y = withNode("K2", matrix("K2", 3, 3, "500,0,.NaN,0,500,240,0,0,1"));
  EXPECT_EQ(errorOf(y), at(y, "   data: [ 500") + ": error: node \"K2\": values must be finite");
  y = withNode("K2", matrix("K2", 3, 3, "500,0,x,0,500,240,0,0,1"));
  EXPECT_EQ(errorOf(y),
            at(y, "   data: [ 500") + ": error: node \"K2\": expected a number, found 'x'");
  y = withNode("D1", matrix("D1", 1, 3, "0,0,0"));
  EXPECT_EQ(errorOf(y),
            at(y, "D1:") + ": error: node \"D1\": expected 4, 5, 8, 12 or 14 coefficients, got 3");
  y = withNode("T", "T: 3\n");
  EXPECT_EQ(errorOf(y),
            at(y, "T:") + ": error: node \"T\": expected an opencv-matrix (rows, cols, dt, data)");
  // Q's baseline disagrees with P2 (0.1 m instead of 0.12 m).
  const StereoCalibration rig = sampleRig();
  const double cx = rig.P1(0, 2);
  const double cy = rig.P1(1, 2);
  const std::string badQ = matrix(
      "Q", 4, 4,
      "1,0,0," + std::to_string(-cx) + ",0,1,0," + std::to_string(-cy) + ",0,0,0,524.1,0,0,10,0");
  y = withNode("Q", badQ);
  EXPECT_EQ(errorOf(y).rfind(at(y, "Q:") + ": error: node \"Q\": Q(3,2) is 10 but P1/P2 "
                                           "(focal 524.1, baseline 0.12 m) gives 8.333333333",
                             0),
            0U)
      << errorOf(y);
  // P2's focal length disagrees with P1.
  y = withNode("P2", matrix("P2", 3, 4,
                            "600,0," + std::to_string(cx) + ",-72,0,600," + std::to_string(cy) +
                                ",0,0,0,1,0"));
  EXPECT_EQ(errorOf(y), at(y, "P2:") +
                            ": error: node \"P2\": P2(0,0) is 600 but P1's focal "
                            "length and a rectified rig gives 524.1");
  y = withNode("X_table_left", matrix("X_table_left", 4, 4, "1,0,0,0,0,1,0,0,0,0,1,0,0,0,1,1"));
  EXPECT_EQ(errorOf(y), at(y, "X_table_left:") +
                            ": error: node \"X_table_left\": the last row must be 0 0 0 1");
  y = withNode("X_table_left", matrix("X_table_left", 4, 4, "2,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1"));
  EXPECT_EQ(errorOf(y), at(y, "X_table_left:") +
                            ": error: node \"X_table_left\": not a rotation matrix (R^T R "
                            "differs from I by 3, det 2)");
  std::string badSize = calibrationToYaml(sampleRig());
  badSize =
      std::regex_replace(badSize, std::regex(R"(image_size: \[[^\]]*\])"), "image_size: [ 640 ]");
  EXPECT_EQ(errorOf(badSize), at(badSize, "image_size:") +
                                  ": error: node \"image_size\": expected [ width, height ]");
}

// The YAML reader (detail/opencv_yaml.hpp): what OpenCV writes reads back, comments and a
// missing header included; what it does not write is an error at its line.
TEST(StereoCalibrationTest, YamlSubsetReadsOpenCvOutputAndRejectsTheRestAtItsLine) {
  const std::string yaml = calibrationToYaml(sampleRig());
  // No header, comments, CRLF line ends: the same calibration.
  std::string edited = yaml.substr(yaml.find("---\n") + 4);
  edited = "# my rig\n" + std::regex_replace(edited, std::regex("\n"), "  # note\r\n");
  EXPECT_EQ(parseCalibration(edited, "c.yml").P2, sampleRig().P2);
  const std::string body = yaml.substr(yaml.find("image_size"));
  struct Case {
    std::string text;
    int line;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"%YAML:1.0\n---\n- 3\n" + body, 3, "a block sequence item"},
      {"image_size: { w: 640 }\n" + body, 1, "a flow mapping"},
      {"a: [ 1, [ 2 ] ]\n" + body, 1, "nested sequences and mappings are not supported"},
      {"a: 1\n\tb: 2\n" + body, 2, "a tab in the indentation"},
      {"a: 1\n---\nb: 2\n", 2, "a second document"},
      {"a: 1\na: 2\n", 2, "key 'a' is given twice (first at line 1)"},
      {"a: 1\n  b: 2\n", 2, "unexpected indentation"},
      {"a: &x 1\n", 1, "anchors, aliases and block scalars are not supported"},
      {"a: [ 1,, 2 ]\n", 1, "an empty item"},
      {"a: \"open\n", 1, "a quoted value is not closed"},
      {"a: b: c\n", 1, "a value cannot hold ': '"},
      {"%TAG ! x\na: 1\n", 1, "unexpected directive"},
      {"a: 1\n...\nb: 2\n", 3, "text after the end of the document"},
  };
  for (const Case& c : cases) {
    const std::string error = errorOf(c.text);
    EXPECT_EQ(error.rfind("scene/calibration.yml:" + std::to_string(c.line) +
                              ": error: not a valid OpenCV YAML file: ",
                          0),
              0U)
        << c.text << "\n -> " << error;
    EXPECT_NE(error.find(c.message), std::string::npos) << c.text << "\n -> " << error;
  }
  // Nesting deeper than any calibration: an error, not a stack overflow.
  std::string deep;
  for (int i = 0; i < 5000; ++i) deep += std::string(static_cast<std::size_t>(i), ' ') + "k:\n";
  EXPECT_NE(errorOf(deep).find("nested deeper than 16 levels"), std::string::npos);
}

// Found by fuzzing (fuzz/regressions/calibration/*): OpenCV's YAML parser threw
// std::length_error for the first two (" o:3\n :") and never returned on the others. Files no
// longer reach OpenCV's parser: each is an error at its line.
TEST(StereoCalibrationTest, InputsThatBrokeOpenCvsParserAreErrorsAtTheirLine) {
  const std::vector<std::pair<std::string, int>> cases = {
      {" o:3\n :", 1},
      {" r:3\n :", 1},
      {" c:5\n:[ - ]\n ", 1},
      {" c:5\n:{ -\n ", 1},
      {"K1: 1\n  : 2\n", 2},
      {"K1: 1\n: 2\n", 2},
      {std::string("%YAML:1.0\n---\x8ai.nan%P2: YAML:0.0\n-}--\ni !!oT: "), 2},
  };
  for (const auto& [yaml, line] : cases) {
    const std::string error = errorOf(yaml);
    EXPECT_EQ(error.rfind("scene/calibration.yml:" + std::to_string(line) +
                              ": error: not a valid OpenCV YAML file: ",
                          0),
              0U)
        << error;
  }
  EXPECT_NE(errorOf("K1: 1\n: 2\n").find("a value without a key (the line starts with ':')"),
            std::string::npos);
}

// Every input the fuzz stage found (fuzz/regressions/calibration: crashes and hangs of OpenCV's
// parser) is a CalibrationError naming the file and a line.
TEST(StereoCalibrationTest, EveryFuzzFindingIsAnErrorAtALine) {
  const auto dir = std::filesystem::path(VISGRAB_SOURCE_DIR) / "fuzz/regressions/calibration";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
    try {
      readCalibration(entry.path());
      ADD_FAILURE() << entry.path() << " was read";
    } catch (const CalibrationError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(entry.path().string() + ":", 0), 0U) << e.what();
    }
  }
  EXPECT_GE(files, 6);
}

TEST(StereoCalibrationTest, MissingFileNamesIt) {
  try {
    readCalibration("/nonexistent/calibration.yml");
    FAIL();
  } catch (const CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read /nonexistent/calibration.yml"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace visgrab::database
