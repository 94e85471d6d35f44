#include "rw/geometry/ac3d_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <system_error>

namespace rw::geometry {
namespace {

namespace fs = std::filesystem;
using rw::math::Vector3D;

/// Fewest bytes a vertex line ("0 0 0"), a surface ("SURF 0\nrefs 0"), a surface's corner line
/// ("0 0 0") and a child object ("OBJECT a\nkids 0") can take, each with its line break.
constexpr std::uint64_t kVertexBytes = 6;
constexpr std::uint64_t kSurfaceBytes = 14;
constexpr std::uint64_t kCornerBytes = 6;
constexpr std::uint64_t kObjectBytes = 16;

/// The words of `line`, a double-quoted string being one word (its quotes removed).
std::optional<std::vector<std::string_view>> ac3dWordsOf(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t pos = 0;
  while (true) {
    const std::size_t start = line.find_first_not_of(" \t\r\f\v", pos);
    if (start == std::string_view::npos) return words;
    if (line[start] == '"') {
      const std::size_t close = line.find('"', start + 1);
      if (close == std::string_view::npos) return std::nullopt;
      words.push_back(line.substr(start + 1, close - start - 1));
      pos = close + 1;
    } else {
      pos = std::min(line.find_first_of(" \t\r\f\v", start), line.size());
      words.push_back(line.substr(start, pos - start));
    }
  }
}

class Ac3dReader {
 public:
  Ac3dReader(const fs::path& file, std::string_view bytes) : file_(file), bytes_(bytes) {}

  std::vector<MeshPart> read() {
    const std::string_view head = bytes_.substr(0, bytes_.find_first_of("\r\n"));
    if (head.size() < 5 || head.substr(0, 4) != "AC3D" ||
        std::isxdigit(static_cast<unsigned char>(head[4])) == 0) {
      failAtLine(file_, 1, "expected \"AC3D\" and a hex version digit (such as \"AC3Db\")");
    }
    nextLine();
    while (const auto words = nextWords()) {
      if ((*words)[0] == "MATERIAL") {
        readMaterial(*words);
      } else if ((*words)[0] == "OBJECT") {
        readObject(*words, Eigen::Affine3d::Identity(), 0);
      } else {
        fail("expected MATERIAL or OBJECT, found " + shown((*words)[0]));
      }
    }
    return std::move(parts_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { failAtLine(file_, line_, what); }

  std::uint64_t bytesLeft() const { return bytes_.size() - pos_; }

  /// The next line (without its line break), or nullopt at the end of the file.
  std::optional<std::string_view> nextLine() {
    if (pos_ >= bytes_.size()) return std::nullopt;
    line_ = nextLineNumber_++;
    const std::size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
    std::string_view line = bytes_.substr(pos_, end - pos_);
    pos_ = std::min(end + 1, bytes_.size());
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }

  /// The words of the next line that is not blank, or nullopt at the end of the file.
  std::optional<std::vector<std::string_view>> nextWords() {
    while (const auto line = nextLine()) {
      auto words = ac3dWordsOf(*line);
      if (!words) fail("a string without its closing '\"'");
      if (!words->empty()) return words;
    }
    return std::nullopt;
  }

  /// The words of the next non-blank line; `what` says what was expected if the file ends.
  std::vector<std::string_view> expectWords(const std::string& what) {
    auto words = nextWords();
    if (!words) fail("the file ends; expected " + what);
    return std::move(*words);
  }

  double number(std::string_view word, const std::string& what) const {
    if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || end != word.data() + word.size() || !std::isfinite(value)) {
      fail("expected a finite number for " + what + ", found " + shown(word));
    }
    return value;
  }

  /// A count or index: a whole number from 0 to `limit`.
  std::uint64_t count(std::string_view word, const std::string& what, std::uint64_t limit) const {
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || end != word.data() + word.size()) {
      fail("expected a whole number of 0 or more for " + what + ", found " + shown(word));
    }
    if (value > limit) {
      fail(what + " " + std::to_string(value) + " is too large; expected at most " +
           std::to_string(limit));
    }
    return value;
  }

  /// Checks that `words` are the keyword and `n` values.
  void expectSize(const std::vector<std::string_view>& words, std::size_t n,
                  const std::string& form) const {
    if (words.size() != n + 1) fail("expected \"" + form + "\"");
  }

  void readMaterial(const std::vector<std::string_view>& words) {
    if (words.size() < 6 || words[2] != "rgb") {
      fail("expected \"MATERIAL \"<name>\" rgb <r> <g> <b> ...\"");
    }
    for (std::size_t k = 3; k < 6; ++k) number(words[k], "a material's rgb");
    ++materials_;
  }

  /// Skips the `size` bytes of a data block, which start on the next line.
  void skipData(std::uint64_t size) {
    const std::size_t start = pos_;
    if (size > bytesLeft()) {
      fail("data of " + std::to_string(size) + " bytes, but only " + std::to_string(bytesLeft()) +
           " bytes follow");
    }
    pos_ += static_cast<std::size_t>(size);
    nextLineNumber_ += static_cast<std::size_t>(
        std::count(bytes_.begin() + static_cast<std::ptrdiff_t>(start),
                   bytes_.begin() + static_cast<std::ptrdiff_t>(pos_), '\n'));
  }

  void readVertices(std::uint64_t n, MeshPart& part) {
    part.vertices.clear();
    part.vertices.reserve(static_cast<std::size_t>(n));
    for (std::uint64_t i = 0; i < n; ++i) {
      const auto words = expectWords("vertex " + std::to_string(i) + " of " + std::to_string(n));
      if (words.size() != 3) fail("expected a vertex \"<x> <y> <z>\"");
      Vector3D p;
      for (int k = 0; k < 3; ++k) {
        p[k] = asFloat(number(words[static_cast<std::size_t>(k)], "a vertex coordinate"));
      }
      if (!p.allFinite()) fail("vertex " + std::to_string(i) + " is not finite in float");
      part.vertices.push_back(p);
    }
  }

  /// The flags of "SURF <flags>" (hexadecimal after "0x", else decimal).
  std::uint64_t surfaceFlags(const std::vector<std::string_view>& words) const {
    if (words[0] != "SURF" || words.size() != 2) fail("expected \"SURF <flags>\"");
    std::string_view text = words[1];
    int base = 10;
    if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
      text.remove_prefix(2);
      base = 16;
    }
    std::uint64_t flags = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), flags, base);
    if (ec != std::errc() || end != text.data() + text.size()) {
      fail("expected surface flags such as 0x10, found " + shown(words[1]));
    }
    if ((flags & 0xFU) > 2U) {
      fail("surface type " + std::to_string(flags & 0xFU) +
           "; expected 0 (polygon), 1 (closed line) or 2 (line)");
    }
    return flags;
  }

  void readSurface(MeshPart& part) {
    const std::uint64_t flags = surfaceFlags(expectWords("SURF"));
    auto words = expectWords("mat or refs");
    if (words[0] == "mat") {
      expectSize(words, 1, "mat <index>");
      if (materials_ == 0) fail("mat refers to a material, but no MATERIAL comes before it");
      count(words[1], "material index", materials_ - 1);
      words = expectWords("refs");
    }
    if (words[0] != "refs") fail("expected \"refs <count>\", found " + shown(words[0]));
    expectSize(words, 1, "refs <count>");
    const std::uint64_t n = count(words[1], "refs", (bytesLeft() + 1) / kCornerBytes);
    if (n == 0 && (flags & 0xFU) == 0U) {  // assimp refused these (an empty face)
      fail("a polygon surface with refs 0; expected at least one corner");
    }
    const std::size_t surfaceLine = line_;
    std::vector<std::uint32_t> corners;
    corners.reserve(static_cast<std::size_t>(n));
    for (std::uint64_t k = 0; k < n; ++k) {
      const auto ref = expectWords("a surface corner \"<vertex index> <u> <v>\"");
      if (ref.size() != 3) fail("expected a surface corner \"<vertex index> <u> <v>\"");
      if (part.vertices.empty()) fail("a surface corner, but the object has no vertices");
      corners.push_back(
          static_cast<std::uint32_t>(count(ref[0], "vertex index", part.vertices.size() - 1)));
      number(ref[1], "u");
      number(ref[2], "v");
    }
    if ((flags & 0xFU) != 0U) return;  // lines give no triangles
    if (!triangulatePolygon(part.vertices, corners, part.triangles, budget_)) {
      failAtLine(file_, surfaceLine, "the polygons are too large to triangulate");
    }
  }

  void readTransform(const std::vector<std::string_view>& words, Eigen::Affine3d& X) {
    if (words[0] == "rot") {
      expectSize(words, 9, "rot <9 numbers, row by row>");
      for (int k = 0; k < 9; ++k) {
        X.linear()(k / 3, k % 3) = asFloat(number(words[static_cast<std::size_t>(k + 1)], "rot"));
      }
    } else {
      expectSize(words, 3, "loc <x> <y> <z>");
      for (int k = 0; k < 3; ++k) {
        X.translation()[k] = asFloat(number(words[static_cast<std::size_t>(k + 1)], "loc"));
      }
    }
  }

  /// Reads one line of an object's body; returns the number of kids once "kids" is read.
  std::optional<std::uint64_t> readObjectLine(const std::vector<std::string_view>& words,
                                              MeshPart& part, Eigen::Affine3d& X) {
    const std::string_view key = words[0];
    if (key == "kids") {
      expectSize(words, 1, "kids <count>");
      return count(words[1], "kids", (bytesLeft() + 1) / kObjectBytes);
    }
    if (key == "name" || key == "texture" || key == "crease" || key == "subdiv") {
      expectSize(words, 1, std::string(key) + " <value>");
      if (key == "crease") number(words[1], "crease");
      if (key == "subdiv" && count(words[1], "subdiv", 64) > 0) {
        fail("subdiv " + std::string(words[1]) +
             ": subdivision surfaces are not supported; expected subdiv 0");
      }
    } else if (key == "texrep" || key == "texoff") {
      expectSize(words, 2, std::string(key) + " <u> <v>");
      number(words[1], std::string(key));
      number(words[2], std::string(key));
    } else if (key == "rot" || key == "loc") {
      readTransform(words, X);
    } else if (key == "data") {
      expectSize(words, 1, "data <byte count>");
      skipData(count(words[1], "data", std::numeric_limits<std::uint64_t>::max()));
    } else if (key == "numvert") {
      expectSize(words, 1, "numvert <count>");
      // A second list would leave the surfaces read so far pointing into the wrong vertices.
      if (vertices_) fail("a second numvert in one object; expected one vertex list");
      vertices_ = true;
      readVertices(count(words[1], "numvert", (bytesLeft() + 1) / kVertexBytes), part);
    } else if (key == "numsurf") {
      expectSize(words, 1, "numsurf <count>");
      const std::uint64_t n = count(words[1], "numsurf", (bytesLeft() + 1) / kSurfaceBytes);
      surfaces_ = surfaces_ || n > 0;
      for (std::uint64_t s = 0; s < n; ++s) readSurface(part);
    } else if (key != "url" && key != "hidden" && key != "locked" && key != "folded") {
      fail("unknown object keyword " + shown(key) +
           "; expected name, data, texture, texrep, texoff, rot, loc, crease, subdiv, url, "
           "numvert, numsurf or kids");
    }
    return std::nullopt;
  }

  void readObject(const std::vector<std::string_view>& header, const Eigen::Affine3d& X_FP,
                  int depth) {
    if (depth > kMaxAc3dDepth) {
      fail("objects nested deeper than " + std::to_string(kMaxAc3dDepth) + " levels");
    }
    if (header.size() != 2 || (header[1] != "world" && header[1] != "poly" &&
                               header[1] != "group" && header[1] != "light")) {
      fail("expected \"OBJECT world\", \"OBJECT poly\", \"OBJECT group\" or \"OBJECT light\"");
    }
    const std::size_t objectLine = line_;
    MeshPart part;
    Eigen::Affine3d X_PO = Eigen::Affine3d::Identity();
    std::optional<std::uint64_t> kids;
    surfaces_ = false;
    vertices_ = false;
    while (!kids) {
      const auto words = nextWords();
      if (!words) {
        fail("the file ends inside the OBJECT of line " + std::to_string(objectLine) +
             "; expected \"kids <count>\"");
      }
      kids = readObjectLine(*words, part, X_PO);
    }
    // As assimp 5.2 places them (the renderer still draws with it): an object with surfaces
    // has its loc added to its vertices (in float) and only its rot in the frame its kids hang
    // from; an object without surfaces (a group) has both in that frame. So a poly's vertices
    // are rot (p + loc) in its parent's frame, and its kids do not move with its loc.
    Eigen::Affine3d X_PK = X_PO;
    if (surfaces_) {
      for (Vector3D& v : part.vertices) {
        for (int k = 0; k < 3; ++k) v[k] = asFloat(v[k] + X_PO.translation()[k]);
      }
      X_PK.translation().setZero();
    }
    part.X_FO = X_FP * X_PK;
    const Eigen::Affine3d X_FK = part.X_FO;
    if (!part.triangles.empty()) parts_.push_back(std::move(part));
    for (std::uint64_t k = 0; k < *kids; ++k) {
      const auto words = expectWords("OBJECT (kid " + std::to_string(k + 1) + " of " +
                                     std::to_string(*kids) + ")");
      if (words[0] != "OBJECT") fail("expected OBJECT, found " + shown(words[0]));
      readObject(words, X_FK, depth + 1);
    }
  }

  const fs::path& file_;
  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;            // the line last read
  std::size_t nextLineNumber_ = 1;  // the line starting at pos_
  std::uint64_t materials_ = 0;
  std::int64_t budget_ = kTriangulationBudget;  // for all of the file's polygons
  std::vector<MeshPart> parts_;
  bool surfaces_ = false;  // the object being read has surfaces
  bool vertices_ = false;  // the object being read has its vertex list
};

}  // namespace

std::vector<MeshPart> readAc3d(const fs::path& file, std::string_view bytes) {
  return Ac3dReader(file, bytes).read();
}

}  // namespace rw::geometry
