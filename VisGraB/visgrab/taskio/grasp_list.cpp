#include "visgrab/taskio/grasp_list.hpp"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "rw/common/numbers.hpp"
#include "rw/common/xml_attributes.hpp"
#include "visgrab/taskio/detail/common.hpp"

namespace visgrab::taskio {

using grasp::GraspKind;
using grasp::GraspRequest;
using rw::math::Q;
using rw::math::Vector3D;

namespace {

/// Largest number of joint values in one list.
constexpr int kMaxJoints = 64;

/// One comma-separated field and the 1-based column where its text starts.
struct Field {
  std::string_view text;
  int column = 0;
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// A problem with one line: where and what.
struct LineError {
  int column = 0;
  std::string message;
};

/// Reads the fields of one line; throws LineError.
class LineReader {
 public:
  LineReader(std::vector<Field> fields, int endColumn)
      : fields_(std::move(fields)), endColumn_(endColumn) {}

  const Field& next(std::string_view what) {
    if (at_ >= fields_.size()) {
      throw LineError{endColumn_, "line ends early: expected " + std::string(what) + " in field " +
                                      std::to_string(at_ + 1)};
    }
    return fields_[at_++];
  }

  std::string text(std::string_view what) {
    const Field& f = next(what);
    if (f.text.empty()) throw LineError{f.column, std::string(what) + " is empty"};
    return std::string(f.text);
  }

  double number(std::string_view what) {
    const Field& f = next(what);
    const auto n = rw::common::parseFiniteNumber(f.text);
    if (!n.error.empty()) {
      throw LineError{f.column, std::string(what) + ": " + n.error + " (expected a finite number)"};
    }
    return n.value;
  }

  int count(std::string_view what, int low, int high) {
    const Field& f = next(what);
    const auto n = rw::common::parseInteger(f.text, low, high);
    if (!n.error.empty()) throw LineError{f.column, std::string(what) + ": " + n.error};
    return static_cast<int>(n.value);
  }

  Vector3D vector(std::string_view what) {
    Vector3D v;
    for (int i = 0; i < 3; ++i) v[i] = number(std::string(what) + " " + "xyz"[i]);
    return v;
  }

  int column() const { return at_ < fields_.size() ? fields_[at_].column : endColumn_; }

  bool atEnd() const { return at_ >= fields_.size(); }

  void finish(std::string_view kind) const {
    if (at_ < fields_.size()) {
      throw LineError{fields_[at_].column, "too many fields for kind " + std::string(kind) +
                                               ": expected " + std::to_string(at_) + ", got " +
                                               std::to_string(fields_.size())};
    }
  }

 private:
  std::vector<Field> fields_;
  std::size_t at_ = 0;
  int endColumn_;
};

/// Splits `line` (comment already removed) at commas and trims blanks around each field.
std::vector<Field> splitFields(std::string_view line) {
  std::vector<Field> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? line.size() : comma;
    std::size_t b = start;
    std::size_t e = end;
    while (b < e && isBlank(line[b])) ++b;
    while (e > b && isBlank(line[e - 1])) --e;
    fields.push_back(Field{line.substr(b, e - b), static_cast<int>(b) + 1});
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

rw::math::Transform3D readTransform(LineReader& in) {
  const Vector3D p = in.vector("position");
  const int column = in.column();
  std::array<double, 4> q{};
  for (std::size_t i = 0; i < 4; ++i) q[i] = in.number(std::string("quaternion ") + "wxyz"[i]);
  std::string error;
  const auto R = detail::quaternionRotation(q[0], q[1], q[2], q[3], error);
  if (!error.empty()) throw LineError{column, error};
  return rw::math::makeTransform(R, p);
}

void readPose(LineReader& in, GraspRequest& r) { r.X_W_tcp = readTransform(in); }

Q readList(LineReader& in, std::string_view what, int low, int high) {
  const int n = in.count(std::string("number of ") + std::string(what) + " values", low, high);
  Q q(n);
  for (int i = 0; i < n; ++i) q[i] = in.number(std::string(what) + "[" + std::to_string(i) + "]");
  return q;
}

GraspRequest readLine(LineReader& in) {
  GraspRequest r;
  r.sceneId = in.text("scene id");
  if (r.sceneId.find_first_of(" \t") != std::string::npos) {
    throw LineError{1, "scene id \"" + r.sceneId + "\" contains blanks"};
  }
  r.method = in.text("method");
  r.id = in.text("grasp id");
  const Field& kindField = in.next("kind");
  const auto kind = kindFromName(kindField.text);
  if (!kind) {
    throw LineError{kindField.column, "unknown kind \"" + std::string(kindField.text) +
                                          "\", expected raw, preshape, pose_q, contacts or jaw"};
  }
  r.kind = *kind;
  switch (r.kind) {
    case GraspKind::kRaw: {
      readPose(in, r);
      r.qOpen = readList(in, "q_open", 1, kMaxJoints);
      const int closedColumn = in.column();
      r.qClosed = readList(in, "q_closed", 1, kMaxJoints);
      if (r.qClosed.size() != r.qOpen.size()) {
        throw LineError{closedColumn, "q_closed has " + std::to_string(r.qClosed.size()) +
                                          " values, expected as many as q_open (" +
                                          std::to_string(r.qOpen.size()) + ")"};
      }
      const int tauColumn = in.column();
      r.tauMax = readList(in, "tau_max", 0, kMaxJoints);
      if (r.tauMax.size() != 0 && r.tauMax.size() != r.qOpen.size()) {
        throw LineError{tauColumn, "tau_max has " + std::to_string(r.tauMax.size()) +
                                       " values, expected 0 (hand default) or " +
                                       std::to_string(r.qOpen.size())};
      }
      break;
    }
    case GraspKind::kPreshape:
      readPose(in, r);
      r.preshape = in.text("pre-shape name");
      break;
    case GraspKind::kPoseAndQ:
      readPose(in, r);
      r.qOpen = readList(in, "q", 1, kMaxJoints);
      break;
    case GraspKind::kContacts: {
      const int n = in.count("number of contacts", 2, 3);
      for (int i = 0; i < n; ++i) {
        grasp::DesiredContact c;
        const std::string name = "contact " + std::to_string(i + 1);
        c.position = in.vector(name + " position");
        const int column = in.column();
        c.direction = in.vector(name + " direction");
        if (c.direction.norm() < 1e-12) throw LineError{column, name + " direction is zero"};
        r.contacts.push_back(c);
      }
      const int column = in.column();
      r.approach = in.vector("approach");
      if (r.approach.norm() < 1e-12) throw LineError{column, "approach direction is zero"};
      break;
    }
    case GraspKind::kJaw: {
      r.X_W_jaw = readTransform(in);
      const int column = in.column();
      r.width = in.number("width");
      if (r.width < 0.0) throw LineError{column, "width is negative, expected an opening in m"};
      if (!in.atEnd()) r.score = in.number("score");
      break;
    }
  }
  in.finish(grasp::kindName(r.kind));
  return r;
}

void checkText(const std::string& text, std::string_view what, const std::string& id) {
  if (text.empty() || text.find_first_of(",#\r\n") != std::string::npos || isBlank(text.front()) ||
      isBlank(text.back())) {
    throw std::invalid_argument("grasp '" + id + "': " + std::string(what) + " \"" + text +
                                "\" cannot be written in a grasp list (empty, or a comma, '#', "
                                "line break or surrounding blank)");
  }
}

void appendNumbers(std::string& line, const double* values, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) line += "," + detail::formatNumber(values[i]);
}

void appendList(std::string& line, const Q& q) {
  line += "," + std::to_string(q.size());
  appendNumbers(line, q.data(), static_cast<std::size_t>(q.size()));
}

void appendPose(std::string& line, const rw::math::Transform3D& X) {
  appendNumbers(line, X.translation().data(), 3);
  Eigen::Quaterniond q(detail::nearestRotation(X.linear()));
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const std::array<double, 4> wxyz = {q.w(), q.x(), q.y(), q.z()};
  appendNumbers(line, wxyz.data(), 4);
}

}  // namespace

std::optional<GraspKind> kindFromName(std::string_view name) {
  for (GraspKind k : {GraspKind::kRaw, GraspKind::kPreshape, GraspKind::kPoseAndQ,
                      GraspKind::kContacts, GraspKind::kJaw}) {
    if (name == grasp::kindName(k)) return k;
  }
  return std::nullopt;
}

GraspFileContents parseGraspList(std::string_view text, const std::filesystem::path& file) {
  GraspFileContents out;
  const std::string fileName = file.string();
  std::map<std::tuple<std::string, std::string, std::string>, int> seen;
  int lineNumber = 0;
  std::size_t start = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") start = 3;
  while (start < text.size()) {
    ++lineNumber;
    const std::size_t newline = text.find('\n', start);
    std::string_view line = text.substr(
        start, newline == std::string_view::npos ? std::string_view::npos : newline - start);
    start = newline == std::string_view::npos ? text.size() : newline + 1;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    std::size_t first = 0;
    while (first < line.size() && isBlank(line[first])) ++first;
    if (first == line.size()) continue;
    try {
      LineReader in(splitFields(line), static_cast<int>(line.size()) + 1);
      GraspRequest r = readLine(in);
      r.sourceFile = fileName;
      r.sourceLine = lineNumber;
      const auto [it, inserted] =
          seen.emplace(std::make_tuple(r.sceneId, r.method, r.id), lineNumber);
      if (!inserted) {
        throw LineError{1, "duplicate grasp id \"" + r.id + "\" for scene " + r.sceneId +
                               " and method " + r.method + " (first on line " +
                               std::to_string(it->second) + ")"};
      }
      out.requests.push_back(std::move(r));
    } catch (const LineError& e) {
      out.rejected.push_back(detail::errorAt(fileName, lineNumber, e.column, e.message));
    }
  }
  return out;
}

GraspFileContents readGraspList(const std::filesystem::path& file) {
  return parseGraspList(detail::readFileOrThrow(file, "the grasp list"), file);
}

std::string formatGraspList(const std::vector<GraspRequest>& requests) {
  std::string out =
      "# VisGraB grasp list (docs/grasp-format.md): scene, method, id, kind, values\n"
      "# raw:      x,y,z, qw,qx,qy,qz, n,q_open(n), n,q_closed(n), k,tau_max(k)\n"
      "# preshape: x,y,z, qw,qx,qy,qz, name\n"
      "# pose_q:   x,y,z, qw,qx,qy,qz, n,q(n)\n"
      "# contacts: c, c x (px,py,pz, dx,dy,dz), ax,ay,az\n"
      "# jaw:      x,y,z, qw,qx,qy,qz, width[, score]\n";
  for (const auto& r : requests) {
    checkText(r.sceneId, "scene id", r.id);
    checkText(r.method, "method", r.id);
    checkText(r.id, "grasp id", r.id);
    std::string line = r.sceneId + "," + r.method + "," + r.id + "," + grasp::kindName(r.kind);
    switch (r.kind) {
      case GraspKind::kRaw:
        appendPose(line, r.X_W_tcp);
        appendList(line, r.qOpen);
        appendList(line, r.qClosed);
        appendList(line, r.tauMax);
        break;
      case GraspKind::kPreshape:
        checkText(r.preshape, "pre-shape name", r.id);
        appendPose(line, r.X_W_tcp);
        line += "," + r.preshape;
        break;
      case GraspKind::kPoseAndQ:
        appendPose(line, r.X_W_tcp);
        appendList(line, r.qOpen);
        break;
      case GraspKind::kContacts:
        if (r.contacts.size() < 2 || r.contacts.size() > 3) {
          throw std::invalid_argument("grasp '" + r.id + "': " + std::to_string(r.contacts.size()) +
                                      " contacts, a grasp list holds 2 or 3");
        }
        line += "," + std::to_string(r.contacts.size());
        for (const auto& c : r.contacts) {
          appendNumbers(line, c.position.data(), 3);
          appendNumbers(line, c.direction.data(), 3);
        }
        appendNumbers(line, r.approach.data(), 3);
        break;
      case GraspKind::kJaw:
        appendPose(line, r.X_W_jaw);
        appendNumbers(line, &r.width, 1);
        if (r.score) appendNumbers(line, &*r.score, 1);
        break;
    }
    out += line + "\n";
  }
  return out;
}

void writeGraspList(const std::vector<GraspRequest>& requests, const std::filesystem::path& file) {
  detail::writeFileOrThrow(file, formatGraspList(requests));
}

}  // namespace visgrab::taskio
