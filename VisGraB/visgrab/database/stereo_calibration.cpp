#include "visgrab/database/stereo_calibration.hpp"

#include <Eigen/LU>
#include <cmath>
#include <opencv2/core.hpp>
#include <sstream>
#include <vector>

#include "rw/common/text_file.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/detail/opencv_yaml.hpp"

namespace visgrab::database {

namespace {

constexpr double kRelTol = 1e-6;

bool near(double a, double b, double scale = 1.0) {
  return std::abs(a - b) <= kRelTol * std::max({std::abs(a), std::abs(b), scale});
}

std::string num(double v) {
  std::ostringstream out;
  out.precision(10);
  out << v;
  return out.str();
}

template <typename M>
bool allFinite(const M& m) {
  return m.allFinite();
}

std::string checkRotation(const char* node, const Eigen::Matrix3d& R) {
  if (!R.allFinite()) return std::string(node) + ": values must be finite";
  const double err = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (err > kRelTol || R.determinant() <= 0) {
    return std::string(node) + ": not a rotation matrix (R^T R differs from I by " + num(err) +
           ", det " + num(R.determinant()) + ")";
  }
  return {};
}

std::string checkCameraMatrix(const char* node, const Eigen::Matrix3d& K) {
  if (!K.allFinite()) return std::string(node) + ": values must be finite";
  if (!(K(0, 0) > 0) || !(K(1, 1) > 0)) {
    return std::string(node) + ": focal lengths must be positive (fx " + num(K(0, 0)) + ", fy " +
           num(K(1, 1)) + ")";
  }
  if (K(1, 0) != 0 || K(2, 0) != 0 || K(2, 1) != 0 || K(2, 2) != 1) {
    return std::string(node) + ": the last row must be 0 0 1 and K(1,0) must be 0";
  }
  return {};
}

std::string checkDistortion(const char* node, const Eigen::VectorXd& D) {
  const auto n = D.size();
  if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14) {
    return std::string(node) + ": expected 4, 5, 8, 12 or 14 coefficients, got " +
           std::to_string(n);
  }
  if (!D.allFinite()) return std::string(node) + ": values must be finite";
  return {};
}

std::string entryMismatch(const char* node, int r, int c, double got, double expected,
                          const std::string& because) {
  return std::string(node) + ": " + node + "(" + std::to_string(r) + "," + std::to_string(c) +
         ") is " + num(got) + " but " + because + " gives " + num(expected);
}

// --------------------------------------------------------------------------- YAML reading

using detail::YamlNode;

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw CalibrationError(file + ": error: " + what);
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  fail(file + ":" + std::to_string(line), what);
}

const YamlNode& requireNode(const YamlNode& root, const char* name, const std::string& file) {
  const YamlNode* node = root.find(name);
  if (node == nullptr) fail(file, "missing node \"" + std::string(name) + "\"");
  return *node;
}

double number(const YamlNode& n, const std::string& file, const std::string& node) {
  const auto v = n.number();
  if (!v) fail(file, n.line, "node \"" + node + "\": expected a number, found '" + n.scalar + "'");
  if (!std::isfinite(*v)) fail(file, n.line, "node \"" + node + "\": values must be finite");
  return *v;
}

int integer(const YamlNode* n, const std::string& file, int line, const std::string& node) {
  const auto v = n == nullptr ? std::nullopt : n->integer();
  if (!v) fail(file, n == nullptr ? line : n->line, "node \"" + node + "\": expected an integer");
  return *v;
}

// An opencv-matrix node as rows x cols values (row-major). `rows`/`cols` < 0 accept any size.
Eigen::MatrixXd readMatrix(const YamlNode& root, const char* name, const std::string& file,
                           int rows, int cols) {
  const YamlNode& node = requireNode(root, name, file);
  const std::string n(name);
  const YamlNode* data = node.find("data");
  if (node.kind != YamlNode::Kind::kMap || node.find("rows") == nullptr ||
      node.find("cols") == nullptr || data == nullptr) {
    fail(file, node.line, "node \"" + n + "\": expected an opencv-matrix (rows, cols, dt, data)");
  }
  const int r = integer(node.find("rows"), file, node.line, n + ".rows");
  const int c = integer(node.find("cols"), file, node.line, n + ".cols");
  const bool vectorOk = rows == -1 && (r == 1 || c == 1) && r > 0 && c > 0;
  if (!vectorOk && (r != rows || c != cols)) {
    fail(file, node.line,
         "node \"" + n + "\": expected a " +
             (rows == -1 ? std::string("1xN or Nx1")
                         : std::to_string(rows) + "x" + std::to_string(cols)) +
             " matrix, got " + std::to_string(r) + "x" + std::to_string(c));
  }
  const std::size_t count = data->kind == YamlNode::Kind::kSequence ? data->items.size() : 1;
  if (data->kind != YamlNode::Kind::kSequence ||
      count != static_cast<std::size_t>(r) * static_cast<std::size_t>(c)) {
    fail(file, data->line,
         "node \"" + n + "\": data must hold rows x cols = " + std::to_string(r * c) +
             " numbers, got " + std::to_string(count));
  }
  Eigen::MatrixXd m(r, c);
  for (int i = 0; i < r * c; ++i) {
    m(i / c, i % c) = number(data->items[static_cast<std::size_t>(i)], file, n);
  }
  return m;
}

void writeMatrix(cv::FileStorage& fs, const char* name, const Eigen::MatrixXd& m) {
  cv::Mat mat(static_cast<int>(m.rows()), static_cast<int>(m.cols()), CV_64F);
  for (int r = 0; r < mat.rows; ++r) {
    for (int c = 0; c < mat.cols; ++c) mat.at<double>(r, c) = m(r, c);
  }
  fs << name << mat;
}

}  // namespace

rw::math::Transform3D StereoCalibration::rectifiedLeftPose() const {
  rw::math::Transform3D X = X_TL;
  X.linear() = X_TL.linear() * R1.transpose();
  return X;
}

double StereoCalibration::baseline() const {
  const double f = P2(0, 0);
  const double t = std::abs(P2(1, 3)) > std::abs(P2(0, 3)) ? P2(1, 3) : P2(0, 3);
  return f != 0 ? std::abs(t / f) : 0.0;
}

std::string StereoCalibration::check() const {
  if (width <= 0 || height <= 0) {
    return "image_size: width and height must be positive, got " + std::to_string(width) + "x" +
           std::to_string(height);
  }
  for (auto [node, why] :
       {std::pair{"K1", checkCameraMatrix("K1", K1)}, std::pair{"K2", checkCameraMatrix("K2", K2)},
        std::pair{"D1", checkDistortion("D1", D1)}, std::pair{"D2", checkDistortion("D2", D2)},
        std::pair{"R", checkRotation("R", R)}, std::pair{"R1", checkRotation("R1", R1)},
        std::pair{"R2", checkRotation("R2", R2)}}) {
    if (!why.empty()) return why;
  }
  if (!T.allFinite()) return "T: values must be finite";
  if (T.norm() == 0) return "T: the baseline must not be zero";
  if (!P1.allFinite()) return "P1: values must be finite";
  if (!P2.allFinite()) return "P2: values must be finite";
  if (!Q.allFinite()) return "Q: values must be finite";
  const double f = P1(0, 0);
  if (!(f > 0)) return "P1: the focal length P1(0,0) must be positive, got " + num(f);
  Eigen::Matrix<double, 3, 4> p1 = Eigen::Matrix<double, 3, 4>::Zero();
  p1 << f, 0, P1(0, 2), 0, 0, f, P1(1, 2), 0, 0, 0, 1, 0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (!near(P1(r, c), p1(r, c), f)) {
        return entryMismatch("P1", r, c, P1(r, c), p1(r, c),
                             "a rectified [f 0 cx 0; 0 f cy 0; 0 0 1 0]");
      }
    }
  }
  const bool vertical = std::abs(P2(1, 3)) > std::abs(P2(0, 3));
  const int axis = vertical ? 1 : 0;
  const double tf = P2(axis, 3);
  if (tf == 0) return "P2: P2(0,3) or P2(1,3) must hold -f * baseline, both are 0";
  Eigen::Matrix<double, 3, 4> p2 = Eigen::Matrix<double, 3, 4>::Zero();
  p2 << f, 0, P2(0, 2), vertical ? 0 : tf, 0, f, P2(1, 2), vertical ? tf : 0, 0, 0, 1, 0;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (!near(P2(r, c), p2(r, c), f)) {
        return entryMismatch("P2", r, c, P2(r, c), p2(r, c),
                             "P1's focal length and a rectified rig");
      }
    }
  }
  const double t = tf / f;
  if (!near(std::abs(t), T.norm())) {
    return "P2: baseline |P2(" + std::to_string(axis) + ",3) / f| = " + num(std::abs(t)) +
           " m but |T| = " + num(T.norm()) + " m";
  }
  const double c1 = vertical ? P1(1, 2) : P1(0, 2);
  const double c2 = vertical ? P2(1, 2) : P2(0, 2);
  Eigen::Matrix4d q;
  q << 1, 0, 0, -P1(0, 2), 0, 1, 0, -P1(1, 2), 0, 0, 0, f, 0, 0, -1.0 / t, (c1 - c2) / t;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (!near(Q(r, c), q(r, c), r == 3 ? std::abs(1.0 / t) : f)) {
        return entryMismatch("Q", r, c, Q(r, c), q(r, c),
                             "P1/P2 (focal " + num(f) + ", baseline " + num(std::abs(t)) + " m)");
      }
    }
  }
  const std::string pose = checkRotation("X_table_left", X_TL.linear());
  if (!pose.empty()) return pose;
  if (!X_TL.translation().allFinite()) return "X_table_left: values must be finite";
  return {};
}

StereoCalibration idealRectifiedRig(double fx, double fy, double cx, double cy, double baseline,
                                    int width, int height, const rw::math::Transform3D& X_TL) {
  for (double v : {fx, fy, cx, cy, baseline}) {
    if (!std::isfinite(v)) throw std::invalid_argument("idealRectifiedRig: non-finite input");
  }
  if (!(fx > 0) || !(fy > 0) || !(baseline > 0) || width <= 0 || height <= 0) {
    throw std::invalid_argument(
        "idealRectifiedRig: focal lengths, baseline and image size must be positive");
  }
  StereoCalibration c;
  c.width = width;
  c.height = height;
  c.K1 << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  c.K2 = c.K1;
  c.D1 = Eigen::VectorXd::Zero(5);
  c.D2 = Eigen::VectorXd::Zero(5);
  c.R.setIdentity();
  c.T = Eigen::Vector3d(-baseline, 0, 0);
  c.R1.setIdentity();
  c.R2.setIdentity();
  // stereoRectify (horizontal rig, R = I): the new focal length is the mean of the cameras' fy;
  // the new principal point centres the image corners, undistorted and reprojected in single
  // precision; CALIB_ZERO_DISPARITY gives both cameras the mean of the two (equal here).
  const double fc = (fy + fy) * 0.5;
  const double nx = width;
  const double ny = height;
  double sumX = 0;
  double sumY = 0;
  for (int i = 0; i < 4; ++i) {
    const auto u = static_cast<float>((i % 2) * (nx - 1));
    const auto v = static_cast<float>((i < 2 ? 0 : 1) * (ny - 1));
    const auto xn = static_cast<float>((u - cx) * (1.0 / fx));
    const auto yn = static_cast<float>((v - cy) * (1.0 / fy));
    sumX += static_cast<float>(fc * static_cast<double>(xn));
    sumY += static_cast<float>(fc * static_cast<double>(yn));
  }
  const double ccx = (nx - 1) / 2 - sumX / 4;
  const double ccy = (ny - 1) / 2 - sumY / 4;
  const double t = -baseline;
  c.P1 << fc, 0, ccx, 0, 0, fc, ccy, 0, 0, 0, 1, 0;
  c.P2 << fc, 0, ccx, t * fc, 0, fc, ccy, 0, 0, 0, 1, 0;
  c.Q << 1, 0, 0, -ccx, 0, 1, 0, -ccy, 0, 0, 0, fc, 0, 0, -1.0 / t, (ccx - ccx) / t;
  c.X_TL = X_TL;
  return c;
}

StereoCalibration parseCalibration(std::string_view yaml, const std::string& displayPath) {
  if (yaml.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    fail(displayPath, "the file is empty");
  }
  // Our own reader of the YAML that cv::FileStorage writes (detail/opencv_yaml.hpp): OpenCV's
  // parser never returns on some malformed input and throws standard exceptions on other
  // (found by fuzzing, fuzz/regressions/calibration), so a file from outside never reaches it.
  YamlNode root;
  try {
    root = detail::parseOpencvYaml(yaml);
  } catch (const detail::YamlError& e) {
    fail(displayPath, e.line(), std::string("not a valid OpenCV YAML file: ") + e.what());
  }
  StereoCalibration c;
  const YamlNode& size = requireNode(root, "image_size", displayPath);
  if (size.kind != YamlNode::Kind::kSequence || size.items.size() != 2) {
    fail(displayPath, size.line, "node \"image_size\": expected [ width, height ]");
  }
  c.width = integer(&size.items[0], displayPath, size.line, "image_size");
  c.height = integer(&size.items[1], displayPath, size.line, "image_size");
  c.K1 = readMatrix(root, "K1", displayPath, 3, 3);
  c.D1 = readMatrix(root, "D1", displayPath, -1, -1).reshaped();
  c.K2 = readMatrix(root, "K2", displayPath, 3, 3);
  c.D2 = readMatrix(root, "D2", displayPath, -1, -1).reshaped();
  c.R = readMatrix(root, "R", displayPath, 3, 3);
  const Eigen::MatrixXd T = readMatrix(root, "T", displayPath, -1, -1);
  if (T.size() != 3) {
    fail(displayPath, root.find("T")->line,
         "node \"T\": expected 3 values, got " + std::to_string(T.size()));
  }
  c.T = T.reshaped();
  c.R1 = readMatrix(root, "R1", displayPath, 3, 3);
  c.R2 = readMatrix(root, "R2", displayPath, 3, 3);
  c.P1 = readMatrix(root, "P1", displayPath, 3, 4);
  c.P2 = readMatrix(root, "P2", displayPath, 3, 4);
  c.Q = readMatrix(root, "Q", displayPath, 4, 4);
  const Eigen::Matrix4d X = readMatrix(root, "X_table_left", displayPath, 4, 4);
  if (X.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    fail(displayPath, root.find("X_table_left")->line,
         "node \"X_table_left\": the last row must be 0 0 0 1");
  }
  c.X_TL.matrix() = X;
  const std::string why = c.check();
  if (!why.empty()) {
    const auto colon = why.find(':');
    const std::string node = why.substr(0, colon);
    const YamlNode* at = root.find(node);
    const std::string where =
        at == nullptr ? displayPath : displayPath + ":" + std::to_string(at->line);
    fail(where, "node \"" + node + "\"" + why.substr(colon));
  }
  return c;
}

StereoCalibration readCalibration(const std::filesystem::path& file) {
  std::string text;
  const std::string why = rw::common::readTextFile(file, text);
  if (!why.empty()) throw CalibrationError("cannot read " + file.string() + ": " + why);
  return parseCalibration(text, file.string());
}

std::string calibrationToYaml(const StereoCalibration& c) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "image_size" << cv::Size(c.width, c.height);
  writeMatrix(fs, "K1", c.K1);
  writeMatrix(fs, "D1", c.D1.transpose());
  writeMatrix(fs, "K2", c.K2);
  writeMatrix(fs, "D2", c.D2.transpose());
  writeMatrix(fs, "R", c.R);
  writeMatrix(fs, "T", c.T);
  writeMatrix(fs, "R1", c.R1);
  writeMatrix(fs, "R2", c.R2);
  writeMatrix(fs, "P1", c.P1);
  writeMatrix(fs, "P2", c.P2);
  writeMatrix(fs, "Q", c.Q);
  writeMatrix(fs, "X_table_left", c.X_TL.matrix());
  return fs.releaseAndGetString();
}

void writeCalibration(const std::filesystem::path& file, const StereoCalibration& calibration) {
  writeFileAtomically(file, calibrationToYaml(calibration));
}

}  // namespace visgrab::database
