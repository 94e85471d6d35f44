#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QElapsedTimer>
#include <QMainWindow>
#include <QString>

#include "scene_view.hpp"
#include "viewer_options.hpp"
#include "visgrab/session/grasp_order.hpp"
#include "visgrab/session/scene_loader.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/view/trial_replay.hpp"

class QLabel;
class QLineEdit;
class QListWidget;
class QPushButton;
class QSlider;
class QSplitter;
class QTableWidget;
class QTimer;
class QToolButton;

namespace visgrab::viewer {

/// The viewer's main window: the scene list with a filter on the left, the 3-D view with the
/// replay controls in the middle, the selected scene's grasps with their outcomes on the right.
class ViewerWindow : public QMainWindow {
  Q_OBJECT

 public:
  /// The paper's three moments of a trial.
  enum class Moment { kPlaced, kClosed, kLifted };

  /// A window over `loaded`; the 3-D view asks for `options`' size (exactly that size when
  /// `options` asks for a screenshot). No scene is open yet.
  ViewerWindow(ViewerData loaded, const ViewerOptions& options, QWidget* parent = nullptr);
  ~ViewerWindow() override;
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  /// Opens the scene with `id` (empty: the database's first scene) and lists its grasps.
  /// @throws database::UnknownSceneError naming the closest ids; rw::common::LoadError or
  ///   std::runtime_error when the scene's files cannot be read.
  void openScene(const std::string& id);
  /// Resolves and replays the open scene's grasp `spec` (an id, or N for the N-th grasp of
  /// `method`, or of all methods when empty). Returns why it cannot be shown (empty: replayed).
  /// @throws std::invalid_argument when there is no such grasp (selectGrasp).
  QString openGrasp(const std::string& spec, const std::string& method);
  /// The replayed trial's outcome with its qualities (outcomeCaption); empty without a replay.
  QString replayOutcome() const;
  /// Why the replay may not be the run's trial (its outcome or simulated time is not the
  /// results'); empty when it is, or without a replay or results.
  QString replayNote() const { return replayNote_; }
  /// Shows a moment of the replayed trial (nothing without one).
  void showMoment(Moment moment);
  /// The 3-D view.
  SceneView& sceneView() { return *view_; }

 private:
  void buildWidgets();
  void buildMenus();
  void filterScenes(const QString& text);
  void sceneSelected();
  void fillGraspTable();
  void fitGraspTable();
  void graspSelected();
  QString replayGrasp(std::size_t index);
  void showReplayedOutcome(std::size_t index);
  void clearReplay();
  void showFrame(std::size_t index);
  void togglePlay();
  void playTick();
  void setPlaying(bool playing);
  void saveScreenshot();
  void showControls();
  void reportError(const QString& what, const QString& message);

  ViewerData data_;
  /// The database's scenes with the hand (made when the first scene opens).
  std::unique_ptr<session::SceneLoader> loader_;
  std::unique_ptr<session::SceneSession> session_;
  std::vector<session::SceneGrasp> grasps_;
  std::optional<view::TrialReplay> replay_;
  std::optional<std::size_t> replayedGrasp_;
  QString replayNote_;
  std::size_t frame_ = 0;
  QElapsedTimer playClock_;
  double playStartTime_ = 0.0;

  QSplitter* splitter_ = nullptr;
  SceneView* view_ = nullptr;
  QLineEdit* filter_ = nullptr;
  QListWidget* scenes_ = nullptr;
  QTableWidget* graspTable_ = nullptr;
  QToolButton* play_ = nullptr;
  QSlider* slider_ = nullptr;
  QPushButton* placed_ = nullptr;
  QPushButton* closed_ = nullptr;
  QPushButton* lifted_ = nullptr;
  QLabel* info_ = nullptr;
  QTimer* timer_ = nullptr;
};

}  // namespace visgrab::viewer
