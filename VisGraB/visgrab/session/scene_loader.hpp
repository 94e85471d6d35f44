#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "rw/loaders/workcell_loader.hpp"
#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/engines/engine_registry.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

/// A database scene with a hand, as the benchmark runs it: loading, trial set-up, grasp order
/// and scene selection, in one place for the runner, the pictures, the command line and the
/// viewer.
namespace visgrab::session {

/// The trial setup the benchmark uses for `hand` in the scene `dwc`: the hand's device,
/// controller, TCP frame and jaw frame (if it declares one) from its grasp description, the
/// simulator options from the dwc's PhysicsEngine properties, the rest GraspTrialSetup's defaults.
rwsim::simulator::GraspTrialSetup trialSetup(const grasp::HandGraspSetup& hand,
                                             const rwsim::dynamics::DynamicWorkCell& dwc);

/// The Include redirects that put `hand` into scenes generated under `databaseRoot`: a
/// generated scene includes the hand it was generated with from the database's hands/<name>/
/// folder (its workcell in scene.wc.xml, its dynamics in scene.dwc.xml). Each such folder with
/// one grasp description gives two redirects, its workcell and dynamics files to `hand`'s
/// (HandGraspSetup::workcellFile, dynamicsFile). None where those files hold the same text as
/// `hand`'s (the hand the database was generated with: the scene as it is), for a hand without
/// its own files, or for a database without hands/ (an original one).
/// @throws rw::common::LoadError for an unreadable grasp description in hands/.
rw::loaders::IncludeRedirects handRedirects(const std::filesystem::path& databaseRoot,
                                            const grasp::HandGraspSetup& hand);

/// Loads the scenes of one database with one hand put in: any hand runs in any scene without
/// generating the database again. The redirects are worked out once (handRedirects). The
/// loader also names the physics engine the scenes' trials run on (SceneSession).
class SceneLoader {
 public:
  /// `db` and `hand` must outlive the loader; `engine` is a name rwsim::engines knows.
  /// @throws rw::common::LoadError as handRedirects; std::invalid_argument as
  /// rwsim::engines::checkEngine.
  SceneLoader(const database::Database& db, const grasp::HandGraspSetup& hand,
              std::string engine = std::string(rwsim::engines::kDefaultEngine));

  /// The database.
  const database::Database& database() const { return *db_; }
  /// The hand.
  const grasp::HandGraspSetup& hand() const { return *hand_; }
  /// The physics engine of the scenes' trials ("ode", "mujoco").
  const std::string& engine() const { return engine_; }
  /// The redirects each scene is loaded with (empty: scenes as they are).
  const rw::loaders::IncludeRedirects& redirects() const { return redirects_; }
  /// ODE's integration step for every scene's trials instead of the scene's own (`visgrab run
  /// --dt`, the time-step study of docs/report.md); nullopt: the scene's. It shows in the
  /// engine's settings, so run.csv records it.
  /// @throws std::invalid_argument unless `dt` is finite and > 0, or if the engine is not ODE
  /// (MuJoCo has its own step, rwsim::mujoco::MujocoOptions).
  void setTimeStep(std::optional<double> dt);
  /// See setTimeStep.
  std::optional<double> timeStep() const { return timeStep_; }
  /// The trial protocol of every scene's trials (`--protocol`; default: the paper's lift).
  /// @throws std::invalid_argument naming the protocol and the hand's description when the
  /// protocol gives an axis in the jaw frame and the hand declares none.
  void setProtocol(rwsim::trial::TrialProtocol protocol);
  /// See setProtocol.
  const rwsim::trial::TrialProtocol& protocol() const { return protocol_; }

  /// The scene's dynamic workcell with the hand in it, hanging from the scene's HandMount frame
  /// as the generated one. A scene that does not include the database's hand (an original or
  /// hand-written one) is loaded as it is and must hold the hand's device.
  /// @throws rw::common::LoadError for unreadable or invalid files; std::runtime_error naming
  /// the scene when the hand cannot be put in (the scene lacks the hand's device; the hand's
  /// dynamics file is missing).
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> load(const database::SceneEntry& entry) const;

 private:
  const database::Database* db_;
  const grasp::HandGraspSetup* hand_;
  std::string engine_;
  rw::loaders::IncludeRedirects redirects_;
  std::optional<double> timeStep_;
  rwsim::trial::TrialProtocol protocol_;
};

}  // namespace visgrab::session
