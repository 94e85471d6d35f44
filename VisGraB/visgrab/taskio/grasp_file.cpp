#include "visgrab/taskio/grasp_file.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include "rw/common/diagnostic_sink.hpp"
#include "visgrab/taskio/detail/common.hpp"
#include "visgrab/taskio/experiment_xml.hpp"
#include "visgrab/taskio/grasp_list.hpp"
#include "visgrab/taskio/rwtask_io.hpp"

namespace visgrab::taskio {

namespace fs = std::filesystem;

namespace {

bool looksLikeXml(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  const auto first = text.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && text[first] == '<';
}

/// The root element of XML text; LoadError unless it is <CartesianTask> or <visgrab>.
rw::common::XmlElement xmlRoot(std::string_view text, const fs::path& file) {
  auto top = detail::parseXmlOrThrow(text, file);
  if (top.size() != 1) {
    throw rw::common::LoadError({detail::errorAt(
        file.string(), top.size() > 1 ? top[1].location.line : 0,
        top.size() > 1 ? top[1].location.column : 0, "expected exactly one root element")});
  }
  const auto name = detail::localName(top.front().name);
  if (name != "CartesianTask" && name != "visgrab") {
    throw rw::common::LoadError({detail::errorAt(
        file.string(), top.front().location.line, top.front().location.column,
        "unknown grasp file: root element <" + top.front().name +
            ">, expected <CartesianTask> (RobWork task) or <visgrab> (VisGraB experiment)")});
  }
  return std::move(top.front());
}

/// The method of an rwtask file: its name without the task suffix.
std::string methodOf(const fs::path& file) {
  std::string name = file.filename().string();
  for (std::string_view suffix : {".rwtask.xml", ".task.xml", ".xml"}) {
    if (name.size() > suffix.size() && name.ends_with(suffix)) {
      return name.substr(0, name.size() - suffix.size());
    }
  }
  return name;
}

void fromRwTask(const rw::common::XmlElement& root, const fs::path& file, GraspFileContents& out) {
  rw::common::DiagnosticSink sink;
  GraspTask task = detail::rwTaskFromElement(root, sink);
  if (sink.hasErrors()) throw rw::common::LoadError(sink.take());
  for (auto& d : sink.take()) out.warnings.push_back(std::move(d));
  const auto scene = stringProperty(task.otherProperties, "SceneID");
  if (!scene || scene->empty()) {
    throw rw::common::LoadError({detail::errorAt(
        file.string(), root.location.line, root.location.column,
        "RobWork task has no root String property SceneID (as VisGraB wrote it); add "
        "<Property><Name>SceneID</Name><Value><String>scene id</String></Value></Property> to "
        "the root <PropertyMap>")});
  }
  for (auto& sub : task.subTasks) {
    if (sub.refframe.empty() || sub.refframe == "WORLD" || sub.targets.empty()) continue;
    out.rejected.push_back(detail::errorAt(
        file.string(), sub.sourceLine, 0,
        "sub-task with refframe \"" + sub.refframe + "\": its " +
            std::to_string(sub.targets.size()) +
            " targets are rejected (only refframe WORLD can be read without the scene)"));
    sub.targets.clear();  // keep the sub-task so that the others keep their ids
  }
  for (auto& r : toGraspRequests(task, *scene, methodOf(file))) {
    r.sourceFile = file.string();
    out.requests.push_back(std::move(r));
  }
}

}  // namespace

GraspFileFormat detectGraspFileFormat(std::string_view text, const fs::path& file) {
  if (!looksLikeXml(text)) return GraspFileFormat::kGraspList;
  return detail::localName(xmlRoot(text, file).name) == "visgrab" ? GraspFileFormat::kExperiment
                                                                  : GraspFileFormat::kRwTask;
}

GraspFileContents readGraspFile(const fs::path& file) {
  const std::string text = detail::readFileOrThrow(file, "the grasp file");
  if (!looksLikeXml(text)) return parseGraspList(text, file);
  const rw::common::XmlElement root = xmlRoot(text, file);
  GraspFileContents out;
  if (detail::localName(root.name) == "visgrab") {
    detail::experimentsFromElement(root, file.string(), out);
  } else {
    fromRwTask(root, file, out);
  }
  return out;
}

GraspFileContents readGraspFolder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw rw::common::LoadError(
        {detail::errorAt(folder.string(), 0, 0, "cannot read the grasp folder: not a folder")});
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.front() == '.') continue;
    if (entry.is_regular_file(ec)) files.push_back(entry.path());
  }
  if (ec) {
    throw rw::common::LoadError(
        {detail::errorAt(folder.string(), 0, 0, "cannot list the grasp folder: " + ec.message())});
  }
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
  GraspFileContents all;
  for (const auto& f : files) {
    GraspFileContents one = readGraspFile(f);
    for (auto& r : one.requests) all.requests.push_back(std::move(r));
    for (auto& d : one.rejected) all.rejected.push_back(std::move(d));
    for (auto& d : one.warnings) all.warnings.push_back(std::move(d));
  }
  return all;
}

GraspFileContents readGraspSources(const std::vector<std::filesystem::path>& paths) {
  GraspFileContents all;
  for (const auto& p : paths) {
    std::error_code ec;
    auto one = std::filesystem::is_directory(p, ec) ? readGraspFolder(p) : readGraspFile(p);
    for (auto& r : one.requests) all.requests.push_back(std::move(r));
    for (auto& d : one.rejected) all.rejected.push_back(std::move(d));
    for (auto& d : one.warnings) all.warnings.push_back(std::move(d));
  }
  return all;
}

}  // namespace visgrab::taskio
