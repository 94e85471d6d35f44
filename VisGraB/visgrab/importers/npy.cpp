#include "visgrab/importers/npy.hpp"

#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

namespace visgrab::importers {

std::string NdArray::shapeText() const {
  std::string out = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i > 0) out += ", ";
    out += std::to_string(shape[i]);
  }
  if (shape.size() == 1) out += ",";
  return out + ")";
}

std::string readFileBytes(const std::filesystem::path& file, std::size_t limit) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ImportError(file.string() + ": cannot open the file");
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (!ec && size > limit) {
    throw ImportError(file.string() + ": the file has " + std::to_string(size) +
                      " bytes, more than the " + std::to_string(limit) + " this reader accepts");
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ImportError(file.string() + ": cannot read the file");
  return std::move(text).str();
}

namespace {

// The parsed header dictionary of an NPY file.
struct NpyHeader {
  std::string descr;
  bool fortranOrder = false;
  std::vector<std::size_t> shape;
};

// A value of the header's Python literal: a string, a bool, a tuple of integers.
struct HeaderValue {
  enum class Kind { kString, kBool, kTuple } kind = Kind::kString;
  std::string text;
  bool flag = false;
  std::vector<std::size_t> numbers;
};

// A strict reader of the dict literal numpy writes ("{'descr': '<f8', 'fortran_order': False,
// 'shape': (3, 4), }"): string keys; string, True/False or tuple-of-integer values.
class HeaderParser {
 public:
  HeaderParser(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  NpyHeader parse() {
    NpyHeader header;
    bool haveDescr = false;
    bool haveOrder = false;
    bool haveShape = false;
    expect('{');
    skipSpace();
    while (peek() != '}') {
      const std::string key = readString();
      expect(':');
      const HeaderValue value = readValue(key);
      if (key == "descr") {
        if (value.kind != HeaderValue::Kind::kString) fail("'descr' is not a string");
        header.descr = value.text;
        haveDescr = true;
      } else if (key == "fortran_order") {
        if (value.kind != HeaderValue::Kind::kBool) fail("'fortran_order' is not True or False");
        header.fortranOrder = value.flag;
        haveOrder = true;
      } else if (key == "shape") {
        if (value.kind != HeaderValue::Kind::kTuple) fail("'shape' is not a tuple of integers");
        header.shape = value.numbers;
        haveShape = true;
      } else {
        fail("unknown key '" + key + "' (expected 'descr', 'fortran_order' and 'shape')");
      }
      skipSpace();
      if (peek() == ',') {
        ++at_;
        skipSpace();
      } else if (peek() != '}') {
        fail("expected ',' or '}'");
      }
    }
    ++at_;
    skipSpace();
    if (at_ != text_.size()) fail("text after the header's closing '}'");
    if (!haveDescr || !haveOrder || !haveShape) {
      fail("the header lacks 'descr', 'fortran_order' or 'shape'");
    }
    return header;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw ImportError(name_ + ": malformed NPY header at byte " + std::to_string(at_) +
                      " of the header: " + what);
  }
  char peek() const { return at_ < text_.size() ? text_[at_] : '\0'; }
  void skipSpace() {
    while (at_ < text_.size() &&
           (text_[at_] == ' ' || text_[at_] == '\n' || text_[at_] == '\t' || text_[at_] == '\r')) {
      ++at_;
    }
  }
  void expect(char c) {
    skipSpace();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++at_;
  }
  std::string readString() {
    skipSpace();
    const char quote = peek();
    if (quote != '\'' && quote != '"') fail("expected a quoted string");
    ++at_;
    const std::size_t start = at_;
    while (at_ < text_.size() && text_[at_] != quote) {
      if (text_[at_] == '\\') fail("escapes in strings are not supported");
      ++at_;
    }
    if (at_ >= text_.size()) fail("unterminated string");
    return std::string(text_.substr(start, at_++ - start));
  }
  HeaderValue readValue(const std::string& key) {
    skipSpace();
    HeaderValue v;
    const char c = peek();
    if (c == '\'' || c == '"') {
      v.text = readString();
      return v;
    }
    if (c == '[') {
      fail("'" + key +
           "' is a list: a structured (record) array, which is not supported; save a plain "
           "numeric array");
    }
    if (c == '(') {
      ++at_;
      v.kind = HeaderValue::Kind::kTuple;
      skipSpace();
      while (peek() != ')') {
        v.numbers.push_back(readInteger());
        skipSpace();
        if (peek() == ',') {
          ++at_;
          skipSpace();
        } else if (peek() != ')') {
          fail("expected ',' or ')' in a tuple");
        }
      }
      ++at_;
      return v;
    }
    for (const auto& [word, flag] : {std::pair{"True", true}, std::pair{"False", false}}) {
      const std::size_t n = std::strlen(word);
      if (text_.substr(at_, n) == word) {
        at_ += n;
        v.kind = HeaderValue::Kind::kBool;
        v.flag = flag;
        return v;
      }
    }
    fail("unexpected value of '" + key + "'");
  }
  std::size_t readInteger() {
    if (!std::isdigit(static_cast<unsigned char>(peek()))) fail("expected a dimension (integer)");
    std::size_t value = 0;
    while (std::isdigit(static_cast<unsigned char>(peek()))) {
      const auto digit = static_cast<std::size_t>(peek() - '0');
      if (value > (std::numeric_limits<std::size_t>::max() - digit) / 10)
        fail("dimension too large");
      value = value * 10 + digit;
      ++at_;
    }
    if (peek() == 'L') ++at_;  // Python 2's long suffix, as old numpy wrote it
    return value;
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t at_ = 0;
};

// How one element is stored.
struct ElementType {
  char kind = 'f';  // 'f' float, 'i' signed, 'u' unsigned, 'b' bool
  std::size_t size = 8;
  bool bigEndian = false;
};

ElementType elementType(const std::string& descr, const std::string& name) {
  const std::string expected =
      " (expected a numeric dtype: '<f8', '<f4', '<i8', '<i4', '|u1', '|b1', ... little or "
      "big-endian)";
  if (descr.find('O') != std::string::npos) {
    throw ImportError(name + ": an object array (dtype '" + descr +
                      "': pickled Python objects); object arrays are never read" + expected);
  }
  if (descr.size() < 2) throw ImportError(name + ": unknown dtype '" + descr + "'" + expected);
  ElementType t;
  std::size_t at = 0;
  switch (descr[0]) {
    case '<':
    case '|':
    case '=':
      at = 1;
      break;
    case '>':
      t.bigEndian = true;
      at = 1;
      break;
    default:
      break;
  }
  t.kind = descr[at];
  const std::string digits = descr.substr(at + 1);
  if (digits.empty() || digits.size() > 2 ||
      digits.find_first_not_of("0123456789") != std::string::npos) {
    throw ImportError(name + ": unsupported dtype '" + descr + "'" + expected);
  }
  t.size = static_cast<std::size_t>(std::stoi(digits));
  const bool ok = (t.kind == 'f' && (t.size == 4 || t.size == 8)) ||
                  ((t.kind == 'i' || t.kind == 'u') &&
                   (t.size == 1 || t.size == 2 || t.size == 4 || t.size == 8)) ||
                  (t.kind == 'b' && t.size == 1);
  if (!ok) throw ImportError(name + ": unsupported dtype '" + descr + "'" + expected);
  return t;
}

template <typename T>
T loadElement(const char* p, bool bigEndian) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, p, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return value;
}

double elementValue(const char* p, const ElementType& t) {
  switch (t.kind) {
    case 'f':
      return t.size == 4 ? static_cast<double>(loadElement<float>(p, t.bigEndian))
                         : loadElement<double>(p, t.bigEndian);
    case 'b':
      return *p != 0 ? 1.0 : 0.0;
    case 'i':
      switch (t.size) {
        case 1:
          return loadElement<std::int8_t>(p, t.bigEndian);
        case 2:
          return loadElement<std::int16_t>(p, t.bigEndian);
        case 4:
          return loadElement<std::int32_t>(p, t.bigEndian);
        default:
          return static_cast<double>(loadElement<std::int64_t>(p, t.bigEndian));
      }
    default:
      switch (t.size) {
        case 1:
          return loadElement<std::uint8_t>(p, t.bigEndian);
        case 2:
          return loadElement<std::uint16_t>(p, t.bigEndian);
        case 4:
          return loadElement<std::uint32_t>(p, t.bigEndian);
        default:
          return static_cast<double>(loadElement<std::uint64_t>(p, t.bigEndian));
      }
  }
}

std::uint32_t littleEndianLength(std::string_view bytes, std::size_t at, std::size_t n) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < n; ++i) {
    value |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
  }
  return value;
}

}  // namespace

NdArray parseNpy(std::string_view bytes, const std::string& name) {
  static constexpr std::string_view kMagic("\x93NUMPY", 6);
  if (bytes.size() < 8 || bytes.substr(0, 6) != kMagic) {
    throw ImportError(name + ": not an NPY file (expected the magic \\x93NUMPY)");
  }
  const int major = static_cast<unsigned char>(bytes[6]);
  const int minor = static_cast<unsigned char>(bytes[7]);
  if (major < 1 || major > 3 || minor != 0) {
    throw ImportError(name + ": NPY format version " + std::to_string(major) + "." +
                      std::to_string(minor) + " (expected 1.0, 2.0 or 3.0)");
  }
  const std::size_t lengthBytes = major == 1 ? 2 : 4;
  if (bytes.size() < 8 + lengthBytes) throw ImportError(name + ": truncated NPY header");
  const std::size_t headerLength = littleEndianLength(bytes, 8, lengthBytes);
  const std::size_t dataStart = 8 + lengthBytes + headerLength;
  if (bytes.size() < dataStart) {
    throw ImportError(name + ": truncated NPY header (" + std::to_string(headerLength) +
                      " bytes announced, " + std::to_string(bytes.size() - 8 - lengthBytes) +
                      " present)");
  }
  const NpyHeader header = HeaderParser(bytes.substr(8 + lengthBytes, headerLength), name).parse();
  const ElementType type = elementType(header.descr, name);

  std::size_t count = 1;
  for (const std::size_t d : header.shape) {
    if (d != 0 && count > kMaxArrayBytes / d) {
      throw ImportError(name + ": shape too large (more than " + std::to_string(kMaxArrayBytes) +
                        " bytes)");
    }
    count *= d;
  }
  if (count > kMaxArrayBytes / type.size) {
    throw ImportError(name + ": shape too large (more than " + std::to_string(kMaxArrayBytes) +
                      " bytes)");
  }
  const std::size_t dataBytes = count * type.size;
  const std::size_t present = bytes.size() - dataStart;
  if (present != dataBytes) {
    NdArray shapeOnly;
    shapeOnly.shape = header.shape;
    throw ImportError(name + ": the data has " + std::to_string(present) + " bytes, expected " +
                      std::to_string(dataBytes) + " for shape " + shapeOnly.shapeText() + " of '" +
                      header.descr + "'");
  }

  NdArray out;
  out.shape = header.shape;
  out.dtype = header.descr;
  out.values.resize(count);
  const char* data = bytes.data() + dataStart;
  if (!header.fortranOrder || header.shape.size() < 2) {
    for (std::size_t i = 0; i < count; ++i)
      out.values[i] = elementValue(data + i * type.size, type);
    return out;
  }
  // Fortran order: the first index varies fastest in the file; walk the file in its order and
  // place each value at its row-major index.
  const std::size_t rank = header.shape.size();
  std::vector<std::size_t> strideC(rank, 1);
  for (std::size_t k = rank - 1; k-- > 0;) strideC[k] = strideC[k + 1] * header.shape[k + 1];
  std::vector<std::size_t> index(rank, 0);
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t c = 0;
    for (std::size_t k = 0; k < rank; ++k) c += index[k] * strideC[k];
    out.values[c] = elementValue(data + i * type.size, type);
    for (std::size_t k = 0; k < rank; ++k) {
      if (++index[k] < header.shape[k]) break;
      index[k] = 0;
    }
  }
  return out;
}

NdArray readNpy(const std::filesystem::path& file) {
  return parseNpy(readFileBytes(file, kMaxArrayBytes + 65536 + 16), file.string());
}

}  // namespace visgrab::importers
