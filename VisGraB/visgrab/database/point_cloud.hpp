#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace visgrab::database {

/// A point cloud file that cannot be read; what() names the file and what was expected.
class PointCloudError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A coloured point cloud as the database stores it (cloud.ply).
struct PointCloud {
  /// Points, metres.
  std::vector<Eigen::Vector3f> points;
  /// Colour of each point: red, green, blue (0..255); the same size as points.
  std::vector<std::array<std::uint8_t, 3>> colours;
  /// The header's comment lines, without "comment ".
  std::vector<std::string> comments;
};

/// The cloud as a PLY file: `ply`, `format binary_little_endian 1.0`, the comments, `element
/// vertex N`, `property float x|y|z`, `property uchar red|green|blue`, `end_header`, then N
/// records of 15 bytes. Open3D, PCL and Meshlab read it as it is.
/// @throws std::invalid_argument if colours and points differ in size or a comment has a line
/// break.
std::string pointCloudToPly(const PointCloud& cloud);

/// Reads the database's PLY layout (pointCloudToPly): binary little-endian, one `vertex` element
/// with exactly the properties float x y z, uchar red green blue in this order, nothing after the
/// last vertex. `displayPath` names the data in messages.
/// @throws PointCloudError naming displayPath and the header line or vertex that is wrong
/// (another layout, a bad count, truncated data).
PointCloud parsePointCloud(std::string_view bytes, const std::string& displayPath);

/// parsePointCloud on a file's content. @throws PointCloudError naming the file.
PointCloud readPointCloud(const std::filesystem::path& file);

}  // namespace visgrab::database
