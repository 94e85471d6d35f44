#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"
#include "rw/math/types.hpp"

namespace visgrab::taskio::detail {

/// Largest accepted deviation of a quaternion's norm from 1 (docs/grasp-format.md).
inline constexpr double kQuaternionTolerance = 1e-3;
/// Largest accepted entry of R^T R - I for a rotation matrix given in a grasp file.
inline constexpr double kRotationTolerance = 1e-3;

/// Shortest decimal text that reads back as exactly `value`.
std::string formatNumber(double value);
/// Numbers separated by single spaces.
std::string formatNumbers(const double* values, std::size_t count);
/// `name` without a namespace prefix ("vg:grasp" -> "grasp").
std::string_view localName(std::string_view name);

/// Rotation of the unit quaternion (w, x, y, z); empty `error` when |q| is within
/// kQuaternionTolerance of 1 (the quaternion is then normalised), else why not.
rw::math::Rotation3D quaternionRotation(double w, double x, double y, double z, std::string& error);
/// Largest entry of |R^T R - I|.
double orthonormalityError(const rw::math::Rotation3D& R);
/// The rotation matrix nearest to `R` (SVD projection).
rw::math::Rotation3D nearestRotation(const rw::math::Rotation3D& R);

/// A source file description for XML positions.
std::shared_ptr<const rw::common::SourceFile> sourceFile(const std::filesystem::path& file);

/// Parses XML text; throws rw::common::LoadError when it is not well-formed.
std::vector<rw::common::XmlElement> parseXmlOrThrow(std::string_view text,
                                                    const std::filesystem::path& file);

/// The first child element whose local name is `name`, or nullptr.
const rw::common::XmlElement* child(const rw::common::XmlElement& element, std::string_view name);

/// XML text of `element` (attributes, text, children) for re-writing kept properties.
void writeElement(std::string& out, const rw::common::XmlElement& element, int indent);

/// An error diagnostic at file:line:column.
rw::common::Diagnostic errorAt(const std::string& file, int line, int column, std::string message);

/// Reads the whole file; throws rw::common::LoadError if it cannot.
std::string readFileOrThrow(const std::filesystem::path& file, std::string_view what);
/// Writes `text` to `file`; throws std::runtime_error if it cannot.
void writeFileOrThrow(const std::filesystem::path& file, const std::string& text);

}  // namespace visgrab::taskio::detail
