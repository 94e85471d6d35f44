#include "visgrab/taskio/detail/common.hpp"

#include <Eigen/SVD>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "rw/common/strings.hpp"
#include "rw/common/text_file.hpp"
#include "rw/common/write_error.hpp"
#include "rw/common/xml_reader.hpp"

#include "rw/common/number_text.hpp"
namespace visgrab::taskio::detail {

std::string formatNumber(double value) {
  if (value == 0.0) return "0";  // also -0
  return rw::common::shortestText(value);
}

std::string formatNumbers(const double* values, std::size_t count) {
  std::string out;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) out += ' ';
    out += formatNumber(values[i]);
  }
  return out;
}

std::string_view localName(std::string_view name) {
  const auto colon = name.rfind(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

rw::math::Rotation3D quaternionRotation(double w, double x, double y, double z,
                                        std::string& error) {
  error.clear();
  const double norm = std::sqrt(w * w + x * x + y * y + z * z);
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > kQuaternionTolerance) {
    error = "quaternion (w x y z) = (" + formatNumber(w) + " " + formatNumber(x) + " " +
            formatNumber(y) + " " + formatNumber(z) + ") has norm " + formatNumber(norm) +
            ", expected a unit quaternion (|q| within 1e-3 of 1)";
    return rw::math::Rotation3D::Identity();
  }
  return Eigen::Quaterniond(w / norm, x / norm, y / norm, z / norm).toRotationMatrix();
}

double orthonormalityError(const rw::math::Rotation3D& R) {
  return (R.transpose() * R - rw::math::Rotation3D::Identity()).cwiseAbs().maxCoeff();
}

rw::math::Rotation3D nearestRotation(const rw::math::Rotation3D& R) {
  const Eigen::JacobiSVD<rw::math::Rotation3D> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  rw::math::Rotation3D U = svd.matrixU();
  const rw::math::Rotation3D V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) = -U.col(2);
  return U * V.transpose();
}

std::shared_ptr<const rw::common::SourceFile> sourceFile(const std::filesystem::path& file) {
  return std::make_shared<const rw::common::SourceFile>(rw::common::SourceFile{file.string(), {}});
}

std::vector<rw::common::XmlElement> parseXmlOrThrow(std::string_view text,
                                                    const std::filesystem::path& file) {
  rw::common::DiagnosticSink sink;
  rw::common::XmlReader reader(rw::common::XmlReaderOptions{});
  auto top = reader.parse(text, sourceFile(file), sink);
  if (!top || sink.hasErrors()) {
    if (!sink.hasErrors()) sink.error({sourceFile(file), 0, 0}, "cannot parse the XML");
    throw rw::common::LoadError(sink.take());
  }
  return std::move(*top);
}

const rw::common::XmlElement* child(const rw::common::XmlElement& element, std::string_view name) {
  for (const auto& c : element.children) {
    if (localName(c.name) == name) return &c;
  }
  return nullptr;
}

void writeElement(std::string& out, const rw::common::XmlElement& element, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  out += pad + "<" + element.name;
  for (const auto& a : element.attributes) {
    out += " " + a.name + "=\"" + rw::common::escapeXml(a.value) + "\"";
  }
  const std::string_view text = rw::common::trimXmlSpace(element.text);
  if (element.children.empty()) {
    out += text.empty() ? "/>\n" : ">" + rw::common::escapeXml(text) + "</" + element.name + ">\n";
    return;
  }
  out += ">";
  if (!text.empty()) out += rw::common::escapeXml(text);
  out += "\n";
  for (const auto& c : element.children) writeElement(out, c, indent + 2);
  out += pad + "</" + element.name + ">\n";
}

rw::common::Diagnostic errorAt(const std::string& file, int line, int column, std::string message) {
  return rw::common::Diagnostic{
      rw::common::Diagnostic::Severity::kError, file, line, column, std::move(message), {}};
}

std::string readFileOrThrow(const std::filesystem::path& file, std::string_view what) {
  std::string text;
  const std::string why = rw::common::readTextFile(file, text);
  if (!why.empty()) {
    throw rw::common::LoadError(
        {errorAt(file.string(), 0, 0, "cannot read " + std::string(what) + ": " + why)});
  }
  return text;
}

void writeFileOrThrow(const std::filesystem::path& file, const std::string& text) {
  errno = 0;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  // The stream keeps no reason; errno holds the failed system call's (EIO if none set it).
  if (!out) throw rw::common::WriteError(file, {errno != 0 ? errno : EIO, std::generic_category()});
}

}  // namespace visgrab::taskio::detail
