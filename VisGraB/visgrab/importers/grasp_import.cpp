#include "visgrab/importers/grasp_import.hpp"

#include <array>
#include <vector>

namespace visgrab::importers {

namespace {

constexpr std::array<ImportFormat, 3> kFormats = {
    ImportFormat::kGraspnet, ImportFormat::kContactGraspnet, ImportFormat::kAcronym};

}  // namespace

const char* importFormatName(ImportFormat format) {
  switch (format) {
    case ImportFormat::kGraspnet:
      return "graspnet";
    case ImportFormat::kContactGraspnet:
      return "contact-graspnet";
    case ImportFormat::kAcronym:
      return "acronym";
  }
  return "graspnet";
}

std::optional<ImportFormat> importFormatFromName(std::string_view name) {
  for (const ImportFormat f : kFormats) {
    if (name == importFormatName(f)) return f;
  }
  return std::nullopt;
}

ImportTarget importTarget(ImportFormat format, const database::Database& db,
                          const std::string& scene, const grasp::HandGraspSetup& hand,
                          const std::string& method) {
  const database::SceneEntry& entry = db.scene(scene);
  const grasp::JawFrame* jaw = hand.jawFrame();
  if (jaw == nullptr) {
    throw ImportError("hand \"" + hand.deviceName() +
                      "\" declares no jaw frame (<JawFrame> in its grasp description); imported "
                      "parallel-jaw grasps need one (e.g. --hand franka)");
  }
  ImportTarget target;
  target.context.sceneId = entry.id;
  target.context.method = method.empty() ? importFormatName(format) : method;
  target.context.jaw = *jaw;
  target.context.hand = hand.deviceName();
  if (format == ImportFormat::kAcronym) {
    if (!entry.source) {
      throw ImportError("scene " + entry.id +
                        " records no source file, so no mesh frame for acronym grasps (a scene "
                        "made by visgrab db from-acronym records it)");
    }
    target.X_W_frame = entry.source->X_W_source;
  } else {
    if (entry.calibration.empty()) {
      throw ImportError("scene " + entry.id + " has no calibration, so no camera frame for " +
                        importFormatName(format) + " grasps");
    }
    target.X_W_frame = db.calibration(entry.id).rectifiedLeftPose();
  }
  return target;
}

std::string sceneMadeFrom(const database::Database& db, const std::filesystem::path& file) {
  const std::string name = file.filename().string();
  std::vector<std::string> found;
  for (const database::SceneEntry& scene : db.list()) {
    if (scene.source && scene.source->file == name) found.push_back(scene.id);
  }
  if (found.size() == 1) return found.front();
  if (found.empty()) {
    throw ImportError("no scene of database " + db.root().string() + " was made from " + name +
                      " (visgrab db from-acronym records each scene's file); give the scene "
                      "with --scene");
  }
  std::string ids;
  for (const auto& id : found) ids += (ids.empty() ? "" : ", ") + id;
  throw ImportError("several scenes of database " + db.root().string() + " were made from " + name +
                    " (" + ids + "); choose one with --scene");
}

ImportResult importGraspFile(ImportFormat format, const std::filesystem::path& file,
                             const ImportTarget& target) {
  switch (format) {
    case ImportFormat::kGraspnet:
      return importGraspnet(file, target.X_W_frame, target.context);
    case ImportFormat::kContactGraspnet:
      return importContactGraspnet(file, target.X_W_frame, target.context);
    case ImportFormat::kAcronym:
      return importAcronym(file, target.X_W_frame, target.context);
  }
  return {};
}

}  // namespace visgrab::importers
