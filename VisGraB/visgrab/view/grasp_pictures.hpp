#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/database/stereo_calibration.hpp"
#include "visgrab/render/gl_renderer.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/view/cameras.hpp"
#include "visgrab/view/trial_replay.hpp"
#include "visgrab/view/workcell_drawing.hpp"
#include "visgrab/visual/visual_mesh.hpp"

namespace visgrab::view {

/// Size and look of the pictures.
struct PictureOptions {
  /// Width of one panel, pixels.
  int width = 640;
  /// Height of one panel's image (a caption bar is added below), pixels.
  int height = 480;
  /// Where the panels look from.
  ViewPreset view = ViewPreset::kOblique;
  /// Draw the hand's contact forces as arrows (length per newton below).
  bool contacts = true;
  /// Arrow length per newton of contact force, m/N (arrows are kept within 1..6 cm).
  double metresPerNewton = 0.01;
  /// Anti-aliasing samples per pixel.
  int samples = 4;
};

/// The colour of an outcome in the pictures: the report's colour (analysis::outcomeColour)
/// as linear RGB for the renderer.
Eigen::Vector3f outcomeColour(rwsim::trial::GraspOutcome outcome);

/// The objects' bounding box in `state`, grown by `margin` metres (where pictures look).
Eigen::AlignedBox3d objectsBox(const session::SceneSession& session, const WorkcellDrawing& drawing,
                               const rw::kinematics::State& state, double margin = 0.03);

/// Appends the contact forces as orange arrows ending at their points, pointing the way each
/// force pushes the body it acts on, `metresPerNewton` long (kept within 1..6 cm).
void addContactArrows(const WorkcellDrawing& drawing, const std::vector<ContactForce>& contacts,
                      double metresPerNewton, render::Scene& scene);

/// One picture of the scene at `state`: everything `style` selects, the contact forces as
/// arrows (pointing at the object they push), seen from `orbit`. No caption.
visual::RgbImage renderState(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                             const rw::kinematics::State& state,
                             const std::vector<ContactForce>& contacts, const DrawStyle& style,
                             const Orbit& orbit, const PictureOptions& options);

/// The paper's three moments of a trial side by side (placed, closed, lifted), each captioned
/// with the phase and time, under a title bar with `title` and the outcome in its colour with
/// Q_lift, Q_GWS and Q_GWS,unit. All panels share one camera, framed on the objects and the hand.
visual::RgbImage graspStrip(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                            const session::SceneSession& session, const TrialReplay& replay,
                            const std::string& title, const PictureOptions& options);

/// One tile of a montage: a grasp and its outcome.
struct MontageTile {
  /// Caption (e.g. "3  s2EGA1-03").
  std::string label;
  /// The resolved grasp; nullopt when it could not be placed (invalid contacts).
  std::optional<rwsim::simulator::GraspParameters> grasp;
  /// The outcome colouring the tile.
  rwsim::trial::GraspOutcome outcome = rwsim::trial::GraspOutcome::kSimulationFailure;
};

/// All grasps of a scene: first an overview with every grasp's approach as an arrow ending at
/// its TCP, coloured by outcome, then one tile per grasp with the hand placed and coloured by
/// its outcome; `columns` tiles per row, a legend of the outcomes present at the bottom.
visual::RgbImage graspMontage(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                              const session::SceneSession& session,
                              const std::vector<MontageTile>& tiles, const std::string& title,
                              const PictureOptions& options, int columns = 4);

/// The grasp drawn into the scene's left stereo image `left` (calibration: K1 and X_TL; lens
/// distortion is not modelled): hand pixels the objects would hide are drawn faintly, visible
/// ones strongly, in the outcome's colour with the hand's outline; the approach as a line to the
/// TCP; a title bar on top.
/// @throws std::invalid_argument if `left` does not have the calibration's size.
visual::RgbImage graspOverlay(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                              const rw::kinematics::State& placed,
                              const rw::math::Transform3D& X_W_tcp, const visual::RgbImage& left,
                              const database::StereoCalibration& calibration,
                              rwsim::trial::GraspOutcome outcome, const std::string& title);

/// A grasp's strip, made by trialStrip.
struct TrialPicture {
  /// The picture.
  visual::RgbImage image;
  /// The outcome of the replayed trial (or kInvalidContacts when the grasp cannot be placed).
  rwsim::trial::GraspOutcome outcome = rwsim::trial::GraspOutcome::kSimulationFailure;
  /// Set when the replay's outcome or simulated time differs from the grasp's trial record
  /// (another build, hand, database or protocol than the run's), or why the grasp could not be
  /// placed.
  std::string note;
};

/// Resolves `grasp` in `session`, replays its trial and draws graspStrip, titled with the scene,
/// method and grasp id. A grasp the contact IK cannot place gives one panel of the scene with
/// the reason. @throws std::invalid_argument for a grasp the hand cannot take as input (an
/// unknown pre-shape, wrong lengths), naming it.
TrialPicture trialStrip(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                        const session::SceneSession& session, const session::SceneGrasp& grasp,
                        const PictureOptions& options);

/// "stable   Q_lift 0.930   Q_GWS 0.4210   Q_GWS,unit 0.0120" (the qualities only for held
/// grasps; "-" for a value that was not computed, NaN).
std::string outcomeCaption(rwsim::trial::GraspOutcome outcome, double qLift, double qGws,
                           double qGwsUnit);

}  // namespace visgrab::view
