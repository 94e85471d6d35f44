#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/common/diagnostic_sink.hpp"
#include "rw/common/xml_tree.hpp"
#include "visgrab/taskio/grasp_task.hpp"

namespace visgrab::taskio {

/// Reads RobWork's CartesianTask XML (`.rwtask.xml`, reference §3.3) from `text`, named `file`
/// in messages. Known properties go into the model's fields; other properties are kept verbatim
/// (a value type RobWork does not know is kept with a warning). Unsupported entities (QTask,
/// Motion, Action, Augmentations) are skipped with a warning. Warnings are appended to
/// `warnings` if given. @throws rw::common::LoadError with file:line:col for malformed XML or
/// any malformed value (the whole file fails, as in RobWork).
GraspTask parseRwTask(std::string_view text, const std::filesystem::path& file,
                      std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// parseRwTask on the content of `file`. @throws rw::common::LoadError (also if unreadable).
GraspTask readRwTask(const std::filesystem::path& file,
                     std::vector<rw::common::Diagnostic>* warnings = nullptr);

/// The task as RobWork's DOM saver writes it: properties in alphabetical order of their names,
/// numbers in shortest round-trip form, transforms as <Pos> + 9-value <Rotation3D>.
std::string formatRwTask(const GraspTask& task);

/// Writes formatRwTask(task) to `file`. @throws std::runtime_error if it cannot be written.
void writeRwTask(const GraspTask& task, const std::filesystem::path& file);

namespace detail {
/// The task below an already parsed <CartesianTask> root; problems go to `sink`.
GraspTask rwTaskFromElement(const rw::common::XmlElement& root, rw::common::DiagnosticSink& sink);
}  // namespace detail

}  // namespace visgrab::taskio
