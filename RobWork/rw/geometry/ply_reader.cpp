#include "rw/geometry/ply_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

namespace rw::geometry {
namespace {

namespace fs = std::filesystem;
using rw::math::Vector3D;

enum class PlyType : std::uint8_t {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat,
  kDouble
};

struct PlyTypeName {
  std::string_view name;
  PlyType type;
};

constexpr std::array<PlyTypeName, 16> kPlyTypeNames = {{{"char", PlyType::kInt8},
                                                        {"int8", PlyType::kInt8},
                                                        {"uchar", PlyType::kUint8},
                                                        {"uint8", PlyType::kUint8},
                                                        {"short", PlyType::kInt16},
                                                        {"int16", PlyType::kInt16},
                                                        {"ushort", PlyType::kUint16},
                                                        {"uint16", PlyType::kUint16},
                                                        {"int", PlyType::kInt32},
                                                        {"int32", PlyType::kInt32},
                                                        {"uint", PlyType::kUint32},
                                                        {"uint32", PlyType::kUint32},
                                                        {"float", PlyType::kFloat},
                                                        {"float32", PlyType::kFloat},
                                                        {"double", PlyType::kDouble},
                                                        {"float64", PlyType::kDouble}}};

constexpr std::string_view kTypeList =
    "char, uchar, short, ushort, int, uint, float, double, int8, uint8, int16, uint16, int32, "
    "uint32, float32 or float64";

std::optional<PlyType> typeNamed(std::string_view name) {
  for (const PlyTypeName& t : kPlyTypeNames) {
    if (t.name == name) return t.type;
  }
  return std::nullopt;
}

std::size_t sizeOf(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kDouble:
      return 8;
    default:
      return 4;
  }
}

bool isInteger(PlyType type) { return type != PlyType::kFloat && type != PlyType::kDouble; }

/// The smallest and largest value of an integer type.
std::pair<double, double> rangeOf(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
      return {-128.0, 127.0};
    case PlyType::kUint8:
      return {0.0, 255.0};
    case PlyType::kInt16:
      return {-32768.0, 32767.0};
    case PlyType::kUint16:
      return {0.0, 65535.0};
    case PlyType::kInt32:
      return {-2147483648.0, 2147483647.0};
    default:
      return {0.0, 4294967295.0};
  }
}

/// What a property is read for.
enum class Role : std::uint8_t { kSkip, kX, kY, kZ, kCorners };

struct Property {
  std::string name;
  bool list = false;
  PlyType countType = PlyType::kUint8;
  PlyType type = PlyType::kFloat;
  Role role = Role::kSkip;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::size_t line = 0;
  std::vector<Property> properties;
};

enum class Format : std::uint8_t { kAscii, kLittleEndian, kBigEndian };

std::vector<std::string_view> plyWordsOf(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t pos = 0;
  while (true) {
    const std::size_t start = line.find_first_not_of(" \t\r\f\v", pos);
    if (start == std::string_view::npos) return words;
    pos = std::min(line.find_first_of(" \t\r\f\v", start), line.size());
    words.push_back(line.substr(start, pos - start));
  }
}

bool isPlySpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/// One face as read: where its corners start in the corner list, how many, where it was.
struct Face {
  std::size_t first = 0;
  std::size_t size = 0;
  std::size_t where = 0;
};

class PlyReader {
 public:
  PlyReader(const fs::path& file, std::string_view bytes) : file_(file), bytes_(bytes) {}

  std::vector<MeshPart> read() {
    readHeader();
    assignRoles();
    checkCounts();
    for (const Element& element : elements_) readElement(element);
    if (ascii()) {
      here();
      if (pos_ < bytes_.size()) {
        failAt(line_,
               "expected the end of the file after the last element, found " + shown(restOfLine()));
      }
    }
    return {buildPart()};
  }

 private:
  bool ascii() const { return format_ == Format::kAscii; }

  [[noreturn]] void failAt(std::size_t where, const std::string& what) const {
    if (ascii()) failAtLine(file_, where, what);
    failAtByte(file_, where, what);
  }

  /// Where the next entry starts: its line (ASCII, blank lines skipped) or byte offset (binary).
  std::size_t here() {
    if (!ascii()) return pos_;
    while (pos_ < bytes_.size() && isPlySpace(bytes_[pos_])) {
      if (bytes_[pos_] == '\n') ++line_;
      ++pos_;
    }
    return line_;
  }

  void readHeader() {
    if (bytes_.substr(0, 3) != "ply") failAtLine(file_, 1, "expected \"ply\" at the start");
    bool haveFormat = false;
    for (std::size_t line = 1;; ++line) {
      const std::size_t end = bytes_.find('\n', pos_);
      if (end == std::string_view::npos) {
        failAtLine(file_, line, "the header ends without a line \"end_header\"");
      }
      std::string_view text = bytes_.substr(pos_, end - pos_);
      pos_ = end + 1;
      line_ = line + 1;
      if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
      const std::vector<std::string_view> words = plyWordsOf(text);
      if (line == 1) {
        if (text != "ply") failAtLine(file_, 1, "expected the line \"ply\", found " + shown(text));
        continue;
      }
      if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
      if (words[0] == "end_header") {
        if (!haveFormat) failAtLine(file_, line, "end_header before a \"format\" line");
        return;
      }
      if (words[0] == "format") {
        readFormat(words, line, haveFormat);
      } else if (words[0] == "element") {
        readElementLine(words, line);
      } else if (words[0] == "property") {
        readPropertyLine(words, line);
      } else {
        failAtLine(file_, line,
                   "unknown header line " + shown(text) +
                       "; expected format, element, property, comment, obj_info or end_header");
      }
    }
  }

  void readFormat(const std::vector<std::string_view>& words, std::size_t line, bool& have) {
    if (have) failAtLine(file_, line, "a second \"format\" line");
    have = true;
    const bool known = words.size() == 3 && words[2] == "1.0";
    if (known && words[1] == "ascii") {
      format_ = Format::kAscii;
    } else if (known && words[1] == "binary_little_endian") {
      format_ = Format::kLittleEndian;
    } else if (known && words[1] == "binary_big_endian") {
      format_ = Format::kBigEndian;
    } else {
      failAtLine(file_, line,
                 "expected \"format ascii 1.0\", \"format binary_little_endian 1.0\" or "
                 "\"format binary_big_endian 1.0\"");
    }
  }

  void readElementLine(const std::vector<std::string_view>& words, std::size_t line) {
    Element element;
    element.line = line;
    if (words.size() == 3) {
      element.name = words[1];
      const std::string_view count = words[2];
      const auto [end, ec] =
          std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (ec == std::errc() && end == count.data() + count.size()) {
        for (const Element& other : elements_) {
          if (other.name == element.name) {
            failAtLine(file_, line, "a second element " + shown(element.name));
          }
        }
        elements_.push_back(std::move(element));
        return;
      }
    }
    failAtLine(file_, line, "expected \"element <name> <count>\" with a count of 0 or more");
  }

  PlyType typeAt(std::string_view name, std::size_t line) const {
    const std::optional<PlyType> type = typeNamed(name);
    if (!type) {
      failAtLine(file_, line,
                 "unknown property type " + shown(name) + "; expected " + std::string(kTypeList));
    }
    return *type;
  }

  void readPropertyLine(const std::vector<std::string_view>& words, std::size_t line) {
    if (elements_.empty()) failAtLine(file_, line, "a property before any element");
    Property property;
    if (words.size() == 5 && words[1] == "list") {
      property.list = true;
      property.countType = typeAt(words[2], line);
      property.type = typeAt(words[3], line);
      property.name = words[4];
      if (!isInteger(property.countType)) {
        failAtLine(file_, line,
                   "a list's count type must be an integer type, not " + shown(words[2]));
      }
    } else if (words.size() == 3 && words[1] != "list") {
      property.type = typeAt(words[1], line);
      property.name = words[2];
    } else {
      failAtLine(file_, line,
                 "expected \"property <type> <name>\" or \"property list <count type> <item "
                 "type> <name>\"");
    }
    elements_.back().properties.push_back(std::move(property));
  }

  void assignRoles() {
    for (Element& element : elements_) {
      if (element.name == "tristrips" && element.count > 0) {
        // assimp turned these into triangles; skipping them would drop the surface unseen.
        failAtLine(file_, element.line,
                   "element tristrips (triangle strips) is not read here; expected the polygons "
                   "in element face");
      }
      if (element.name == "vertex") {
        for (const auto& [name, role] :
             {std::pair{"x", Role::kX}, {"y", Role::kY}, {"z", Role::kZ}}) {
          Property* found = nullptr;
          for (Property& p : element.properties) {
            if (p.name == name) found = &p;
          }
          if (found == nullptr || found->list) {
            failAtLine(file_, element.line,
                       "element vertex needs the scalar properties x, y and z; " +
                           std::string(found == nullptr ? "there is no " : "a list is not ") +
                           name);
          }
          found->role = role;
        }
      } else if (element.name == "face") {
        Property* found = nullptr;
        for (Property& p : element.properties) {
          if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) found = &p;
        }
        if (found == nullptr || !isInteger(found->type)) {
          failAtLine(file_, element.line,
                     "element face needs a list property vertex_indices (or vertex_index) of an "
                     "integer type");
        }
        found->role = Role::kCorners;
      }
    }
  }

  /// Each entry takes at least 2 bytes per value in ASCII (a digit and a separator; the last
  /// value of the file may end it), in binary the sizes of its scalars and list counts.
  void checkCounts() const {
    const std::uint64_t left = bytes_.size() - pos_ + (ascii() ? 1 : 0);
    std::uint64_t used = 0;
    for (const Element& element : elements_) {
      std::uint64_t perEntry = 0;
      for (const Property& p : element.properties) {
        perEntry += ascii() ? 2 : sizeOf(p.list ? p.countType : p.type);
      }
      if (perEntry == 0) continue;
      const std::uint64_t room = (left - used) / perEntry;
      if (element.count > room) {
        failAtLine(file_, element.line,
                   "element " + shown(element.name) + " announces " +
                       std::to_string(element.count) + " entries of at least " +
                       std::to_string(perEntry) + " bytes each, but only " +
                       std::to_string(bytes_.size() - pos_) +
                       " bytes follow the header; expected at most " + std::to_string(room));
      }
      used += element.count * perEntry;
    }
  }

  std::string describe(const Element& element, std::uint64_t entry, const Property& p) const {
    return "element " + shown(element.name) + " entry " + std::to_string(entry) + ", property " +
           shown(p.name);
  }

  double readBinary(PlyType type, const Element& element, std::uint64_t entry, const Property& p) {
    const std::size_t size = sizeOf(type);
    if (bytes_.size() - pos_ < size) {
      failAt(pos_, "the file ends inside " + describe(element, entry, p) + "; expected " +
                       std::to_string(size) + " more bytes");
    }
    std::array<char, 8> raw{};
    std::memcpy(raw.data(), bytes_.data() + pos_, size);
    pos_ += size;
    const bool big = format_ == Format::kBigEndian;
    if (big != (std::endian::native == std::endian::big))
      std::reverse(raw.begin(), raw.begin() + size);
    const auto as = [&raw](auto value) {
      std::memcpy(&value, raw.data(), sizeof value);
      return static_cast<double>(value);
    };
    switch (type) {
      case PlyType::kInt8:
        return as(std::int8_t{});
      case PlyType::kUint8:
        return as(std::uint8_t{});
      case PlyType::kInt16:
        return as(std::int16_t{});
      case PlyType::kUint16:
        return as(std::uint16_t{});
      case PlyType::kInt32:
        return as(std::int32_t{});
      case PlyType::kUint32:
        return as(std::uint32_t{});
      case PlyType::kFloat:
        return as(float{});
      default:
        return as(double{});
    }
  }

  /// The text from pos_ to the end of its line.
  std::string_view restOfLine() const {
    const std::size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
    return bytes_.substr(pos_, end - pos_);
  }

  /// Skips blanks up to the end of the line (each entry of an ASCII body is one line).
  void skipBlanks() {
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && isPlySpace(bytes_[pos_])) ++pos_;
  }

  /// Checks that the entry's line holds nothing more and moves to the next line.
  void endEntry(const Element& element, std::uint64_t entry) {
    skipBlanks();
    if (pos_ == bytes_.size()) return;
    if (bytes_[pos_] != '\n') {
      failAt(line_, "expected the end of the line after element " + shown(element.name) +
                        " entry " + std::to_string(entry) + " (one entry per line), found " +
                        shown(restOfLine()));
    }
    ++pos_;
    ++line_;
  }

  double readAscii(PlyType type, const Element& element, std::uint64_t entry, const Property& p) {
    skipBlanks();
    const std::size_t line = line_;
    if (pos_ == bytes_.size() || bytes_[pos_] == '\n') {
      failAt(line, "the line ends before " + describe(element, entry, p) +
                       "; expected one entry per line");
    }
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !isPlySpace(bytes_[pos_])) ++pos_;
    std::string_view word = bytes_.substr(start, pos_ - start);
    if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
    const char* end = word.data() + word.size();
    if (isInteger(type)) {
      std::int64_t value = 0;
      const auto [ptr, ec] = std::from_chars(word.data(), end, value);
      const auto [low, high] = rangeOf(type);
      const auto v = static_cast<double>(value);
      if (ec == std::errc() && ptr == end && v >= low && v <= high) return v;
      failAt(line, describe(element, entry, p) + ": expected an integer from " +
                       std::to_string(static_cast<std::int64_t>(low)) + " to " +
                       std::to_string(static_cast<std::int64_t>(high)) + ", found " + shown(word));
    }
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(word.data(), end, value);
    if (ec != std::errc() || ptr != end) {
      failAt(line, describe(element, entry, p) + ": expected a number, found " + shown(word));
    }
    return value;
  }

  double readValue(PlyType type, const Element& element, std::uint64_t entry, const Property& p) {
    return ascii() ? readAscii(type, element, entry, p) : readBinary(type, element, entry, p);
  }

  void readList(const Element& element, std::uint64_t entry, const Property& p) {
    if (ascii()) skipBlanks();
    const std::size_t where = ascii() ? line_ : pos_;
    const double count = readValue(p.countType, element, entry, p);
    if (count < 0.0) failAt(where, describe(element, entry, p) + ": a list of negative length");
    const auto items = static_cast<std::uint64_t>(count);
    const std::uint64_t itemSize = ascii() ? 2 : sizeOf(p.type);
    const std::uint64_t left = bytes_.size() - pos_ + (ascii() ? 1 : 0);
    if (items > left / itemSize) {
      failAt(where, describe(element, entry, p) + ": a list of " + std::to_string(items) +
                        " items is longer than the rest of the file (" +
                        std::to_string(bytes_.size() - pos_) + " bytes) could hold");
    }
    if (p.role != Role::kCorners) {
      if (!ascii()) {
        pos_ += static_cast<std::size_t>(items * itemSize);
        return;
      }
      for (std::uint64_t k = 0; k < items; ++k) readAscii(p.type, element, entry, p);
      return;
    }
    if (items == 0) {  // assimp's triangulation aborts the program on an empty face
      failAt(where, "face " + std::to_string(entry) +
                        " has no corners; expected a list of vertex indices");
    }
    faces_.push_back({corners_.size(), static_cast<std::size_t>(items), where});
    for (std::uint64_t k = 0; k < items; ++k) {
      const double index = readValue(p.type, element, entry, p);
      if (index < 0.0) {
        failAt(where, "face " + std::to_string(entry) + ": vertex index " +
                          std::to_string(static_cast<std::int64_t>(index)) +
                          " is negative; expected an index from 0");
      }
      corners_.push_back(static_cast<std::uint32_t>(index));
    }
  }

  void readElement(const Element& element) {
    if (element.properties.empty()) return;  // nothing to read, however many entries
    const bool isVertex = element.name == "vertex";
    if (isVertex) vertices_.reserve(static_cast<std::size_t>(element.count));
    for (std::uint64_t entry = 0; entry < element.count; ++entry) {
      const std::size_t where = here();
      Vector3D point = Vector3D::Zero();
      for (const Property& p : element.properties) {
        if (p.list) {
          readList(element, entry, p);
          continue;
        }
        const double value = readValue(p.type, element, entry, p);
        if (p.role == Role::kX || p.role == Role::kY || p.role == Role::kZ) {
          point[static_cast<int>(p.role) - static_cast<int>(Role::kX)] = asFloat(value);
        }
      }
      if (ascii()) endEntry(element, entry);
      if (isVertex) {
        if (!point.allFinite()) {
          failAt(where, "vertex " + std::to_string(entry) +
                            " has a non-finite coordinate (in float); expected finite x, y, z");
        }
        vertices_.push_back(point);
      }
    }
  }

  MeshPart buildPart() const {
    MeshPart part;
    part.vertices = vertices_;
    std::int64_t budget = kTriangulationBudget;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const Face& face = faces_[f];
      const std::span<const std::uint32_t> corners(corners_.data() + face.first, face.size);
      for (const std::uint32_t index : corners) {
        if (index >= vertices_.size()) {
          failAt(face.where, "face " + std::to_string(f) + ": vertex index " +
                                 std::to_string(index) +
                                 " is out of range; expected an index below " +
                                 std::to_string(vertices_.size()) + " (the number of vertices)");
        }
      }
      if (!triangulatePolygon(part.vertices, corners, part.triangles, budget)) {
        failAt(face.where, "face " + std::to_string(f) + " of " + std::to_string(face.size) +
                               " corners: the polygons are too large to triangulate");
      }
    }
    return part;
  }

  const fs::path& file_;
  std::string_view bytes_;
  Format format_ = Format::kAscii;
  std::vector<Element> elements_;
  std::size_t pos_ = 0;   // the next byte to read
  std::size_t line_ = 1;  // the line of pos_
  std::vector<Vector3D> vertices_;
  std::vector<std::uint32_t> corners_;  // every face's corners, one face after the other
  std::vector<Face> faces_;
};

}  // namespace

std::vector<MeshPart> readPly(const fs::path& file, std::string_view bytes) {
  return PlyReader(file, bytes).read();
}

}  // namespace rw::geometry
