#include "import_commands.hpp"

#include <filesystem>
#include <iostream>
#include <string>

#include "cli_common/data_folder.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/importers/grasp_import.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace visgrab::app {

namespace {

namespace fs = std::filesystem;

int runImport(const Arguments& a) {
  const std::vector<std::string> positionals = a.positionals();
  a.requirePositionals(2, "FORMAT and FILE");
  const auto format = importers::importFormatFromName(positionals[0]);
  if (!format) {
    throw UsageError("unknown format \"" + positionals[0] +
                     "\", expected graspnet, contact-graspnet or acronym");
  }
  const fs::path file = positionals[1];
  const auto scene = a.option("scene");
  if (!scene && *format != importers::ImportFormat::kAcronym) {
    throw UsageError(std::string(importers::importFormatName(*format)) +
                     " grasps are in a scene's camera frame: give the scene with --scene ID");
  }
  const fs::path data = dataFolder(a);
  const auto handText = a.option("hand");
  const fs::path hand = handOptionPath(handText ? *handText : "franka", data);
  const fs::path out = a.option("out").value();

  const database::Database db = database::Database::openAny(a.option("db").value());
  const std::string sceneId = scene ? *scene : importers::sceneMadeFrom(db, file);
  const auto setup = grasp::loadHandGraspSetup(hand);
  const importers::ImportTarget target =
      importers::importTarget(*format, db, sceneId, *setup, a.option("method").value_or(""));
  const importers::ImportResult result = importers::importGraspFile(*format, file, target);
  for (const auto& r : result.rejected) std::cerr << r.format() << "\n";
  taskio::writeGraspList(result.grasps, out);
  if (result.grasps.empty() && result.rejected.empty()) {
    std::cerr << "warning: " << file.string()
              << " holds no grasp; the grasp list written is empty (a run of it exits 1)\n";
  }
  std::cout << result.grasps.size() << " grasps imported, " << result.rejected.size()
            << " rejected; scene " << target.context.sceneId << ", method " << target.context.method
            << ", written to " << out.string() << "\n";
  return result.grasps.empty() && !result.rejected.empty() ? 1 : 0;
}

}  // namespace

void addImportCommands(CommandLine& cli) {
  CLI::App& cmd = cli.addCommand(
      nullptr, "import",
      "Grasps of today's methods' files as a grasp list of parallel-jaw grasps "
      "(docs/grasp-format.md, \"Importing grasps\"): graspnet (graspnetAPI's GraspGroup .npy, "
      "camera frame), contact-graspnet (a plain .npz of grasps, scores[, widths, segments], "
      "camera frame), acronym (ACRONYM's .h5 or GraspGen's .json, the object's mesh frame). Each "
      "bad grasp is rejected alone (file: grasp INDEX: why); exit 1 when every grasp was.",
      guarded(runImport));
  cmd.add_option("FORMAT", "graspnet, contact-graspnet or acronym")->required()->type_name("");
  cmd.add_option("FILE", "The method's grasp file")->required()->type_name("");
  cmd.add_option("--db", kDatabaseOptionHelp)->required()->type_name("DIR|MANIFEST");
  cmd.add_option("--scene",
                 "The scene the grasps are for (required for graspnet and contact-graspnet: "
                 "their camera is the scene's rectified left camera; acronym: default the scene "
                 "made from FILE by `visgrab db from-acronym`)")
      ->type_name("ID");
  cmd.add_option("--out", "The grasp list to write (docs/grasp-format.md)")
      ->required()
      ->type_name("GRASPS.csv");
  cmd.add_option("--hand",
                 "The hand whose jaw frame places the grasps (its stroke bounds the width; "
                 "GraspNet's depth is measured to its fingertips): a name in DATA/hands, a "
                 "folder or a grasp description (default: franka)")
      ->type_name("NAME|DIR|GRASP.xml");
  cmd.add_option("--method", "The grasps' method name (default: the format's name)")
      ->type_name("NAME");
  addDataOption(cmd);
}

}  // namespace visgrab::app
