#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rwsim/trial/trial_protocol.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/trial_record.hpp"
#include "visgrab/taskio/grasp_file.hpp"

/// The Qt viewer of scenes, grasps and trial outcomes (docs/viewer.md).
namespace visgrab::viewer {

/// A command-line mistake: main prints it with the usage and exits with code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What the command line asks for.
struct ViewerOptions {
  /// --db: the scene database (folder or original manifest).
  std::optional<std::filesystem::path> database;
  /// --scene: the scene shown first.
  std::optional<std::string> scene;
  /// --results: a run's result folder (outcomes; default database, grasp files and hand).
  std::optional<std::filesystem::path> results;
  /// --grasps (repeatable): grasp files or folders.
  std::vector<std::filesystem::path> grasps;
  /// --hand: the hand's grasp description.
  std::optional<std::filesystem::path> hand;
  /// --grasp: the grasp shown first (an id, or N for the scene's N-th grasp).
  std::optional<std::string> grasp;
  /// --method: the method --grasp counts in (empty: all).
  std::string method;
  /// --protocol: the trial protocol replays use (lift, a name in DATA/protocols or a file).
  std::optional<std::string> protocol;
  /// --screenshot: save one frame of the 3-D view to this PNG and exit.
  std::optional<std::filesystem::path> screenshot;
  /// --size: the 3-D view's size in (device-independent) pixels.
  int width = 960;
  /// See width.
  int height = 720;
  /// --help or -h.
  bool help = false;
  /// The help text, when help was asked for.
  std::string helpText;
};

/// The viewer's command line (CLI11): every option bound to its field of `options` (which must
/// outlive the app), with its type, default and help.
std::unique_ptr<CLI::App> makeViewerApp(ViewerOptions& options);

/// Parses the arguments (without the program name).
/// @throws UsageError naming the option and what was expected.
ViewerOptions parseViewerOptions(const std::vector<std::string>& args);

/// The usage lines printed after a command-line mistake.
std::string usageLine();

/// Everything the viewer shows, loaded before the window opens.
struct ViewerData {
  /// The scene database.
  std::unique_ptr<database::Database> database;
  /// Where it was opened from.
  std::filesystem::path databasePath;
  /// The hand's grasp description.
  std::unique_ptr<grasp::HandGraspSetup> hand;
  /// The grasps of every grasp file (empty when none were given).
  taskio::GraspFileContents grasps;
  /// True when grasp files were given (by --grasps or by the results).
  bool haveGraspFiles = false;
  /// The run's results, when --results was given.
  std::optional<results::RunResults> results;
  /// The physics engine trials replay on: the run's (run.csv), else ODE.
  std::string engine = "ode";
  /// The trial protocol trials replay with: the run's (results::replayProtocol), else
  /// --protocol, else the lift.
  rwsim::trial::TrialProtocol protocol;
  /// Why no trial can be replayed (the run's protocol is not found); empty when they can.
  std::string replayProblem;
  /// Problems that did not stop loading (rejected grasps, result warnings), one line each.
  std::vector<std::string> warnings;
};

/// Opens the database, the hand, the grasp files and the results `options` name (the results'
/// recorded sources fill in what the options leave out), and finds the protocol replays use: a
/// run's protocol that is not found sets replayProblem (the data can be browsed, no trial
/// replayed).
/// @throws UsageError when --grasp is given but no grasp files are known, or for an unknown
///   --protocol name; rw::common::LoadError or std::runtime_error for inputs that cannot be read,
///   and std::runtime_error for a --protocol that is not the run's (another hash).
ViewerData loadViewerData(const ViewerOptions& options);

}  // namespace visgrab::viewer
