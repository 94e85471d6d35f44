#include "visgrab/database/point_cloud.hpp"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace visgrab::database {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the PLY writer and reader copy little-endian floats as they are in memory");

constexpr std::size_t kVertexBytes = 3 * sizeof(float) + 3;

// The header lines after the format and comments, in order.
constexpr std::string_view kProperties[] = {"property float x",     "property float y",
                                            "property float z",     "property uchar red",
                                            "property uchar green", "property uchar blue"};

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw PointCloudError(where + ": error: " + what);
}

}  // namespace

std::string pointCloudToPly(const PointCloud& cloud) {
  if (cloud.colours.size() != cloud.points.size()) {
    throw std::invalid_argument("point cloud: " + std::to_string(cloud.points.size()) +
                                " points but " + std::to_string(cloud.colours.size()) + " colours");
  }
  std::string out = "ply\nformat binary_little_endian 1.0\n";
  for (const std::string& c : cloud.comments) {
    if (c.find_first_of("\r\n") != std::string::npos) {
      throw std::invalid_argument("point cloud: a comment must be one line: \"" + c + "\"");
    }
    out += "comment " + c + "\n";
  }
  out += "element vertex " + std::to_string(cloud.points.size()) + "\n";
  for (std::string_view p : kProperties) out += std::string(p) + "\n";
  out += "end_header\n";
  const std::size_t start = out.size();
  out.resize(start + kVertexBytes * cloud.points.size());
  char* data = out.data() + start;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const float v = cloud.points[i][k];
      std::memcpy(data, &v, sizeof v);
      data += sizeof v;
    }
    for (int k = 0; k < 3; ++k) *data++ = static_cast<char>(cloud.colours[i][k]);
  }
  return out;
}

PointCloud parsePointCloud(std::string_view bytes, const std::string& displayPath) {
  PointCloud cloud;
  std::size_t pos = 0;
  int lineNumber = 0;
  // The next header line without its '\n'; fails at the end of the data.
  auto nextLine = [&]() {
    const std::size_t end = bytes.find('\n', pos);
    ++lineNumber;
    if (end == std::string_view::npos) {
      fail(displayPath, "the PLY header ends before end_header (truncated, or not a PLY file)");
    }
    std::string_view line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    return line;
  };
  auto where = [&]() { return displayPath + ":" + std::to_string(lineNumber); };
  if (bytes.substr(0, 4) != "ply\n" && bytes.substr(0, 5) != "ply\r\n") {
    fail(displayPath, "not a PLY file (it must start with the line \"ply\")");
  }
  nextLine();
  std::string_view line = nextLine();
  if (line != "format binary_little_endian 1.0") {
    fail(where(), "\"" + std::string(line) +
                      "\": expected \"format binary_little_endian 1.0\" (the database's "
                      "point cloud layout)");
  }
  line = nextLine();
  while (line.substr(0, 8) == "comment " || line == "comment" || line.substr(0, 8) == "obj_info") {
    if (line.substr(0, 8) == "comment ") cloud.comments.emplace_back(line.substr(8));
    line = nextLine();
  }
  std::size_t count = 0;
  {
    std::istringstream in{std::string(line)};
    std::string element, name, rest;
    long long n = -1;
    in >> element >> name >> n;
    if (element != "element" || name != "vertex" || !in || n < 0 || (in >> rest)) {
      fail(where(), "\"" + std::string(line) + R"(": expected "element vertex N")");
    }
    count = static_cast<std::size_t>(n);
  }
  for (std::string_view expected : kProperties) {
    line = nextLine();
    if (line != expected) {
      fail(where(), "\"" + std::string(line) + "\": expected \"" + std::string(expected) +
                        "\" (points are float x y z, uchar red green blue)");
    }
  }
  line = nextLine();
  if (line != "end_header") {
    fail(where(), "\"" + std::string(line) +
                      R"(": expected "end_header" (one vertex element with six properties))");
  }
  const std::size_t available = bytes.size() - pos;
  if (count > available / kVertexBytes || available != count * kVertexBytes) {
    fail(displayPath, "the header announces " + std::to_string(count) + " vertices of " +
                          std::to_string(kVertexBytes) + " bytes (" +
                          std::to_string(count * kVertexBytes) + " bytes) but " +
                          std::to_string(available) + " bytes follow it" +
                          (available < count * kVertexBytes ? " (truncated)" : ""));
  }
  cloud.points.resize(count);
  cloud.colours.resize(count);
  const char* data = bytes.data() + pos;
  for (std::size_t i = 0; i < count; ++i) {
    for (int k = 0; k < 3; ++k) {
      float v = 0.0f;
      std::memcpy(&v, data, sizeof v);
      data += sizeof v;
      cloud.points[i][k] = v;
    }
    for (int k = 0; k < 3; ++k) cloud.colours[i][k] = static_cast<std::uint8_t>(*data++);
  }
  return cloud;
}

PointCloud readPointCloud(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file.string(), "cannot open the point cloud");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(file.string(), "cannot read the point cloud");
  return parsePointCloud(bytes, file.string());
}

}  // namespace visgrab::database
