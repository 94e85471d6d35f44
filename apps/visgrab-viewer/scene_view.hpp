#pragma once

#include <memory>
#include <vector>

#include <QOpenGLWidget>
#include <QPoint>
#include <QString>

#include <Eigen/Geometry>

#include "rw/kinematics/state.hpp"
#include "visgrab/render/gl_renderer.hpp"
#include "visgrab/session/scene_session.hpp"
#include "visgrab/view/cameras.hpp"
#include "visgrab/view/trial_replay.hpp"
#include "visgrab/view/workcell_drawing.hpp"

namespace visgrab::viewer {

/// The 3-D view: a scene session's workcell drawn by GlRenderer at one state, with the hand's
/// contact forces as arrows, seen from an orbit camera the mouse and keys move.
///
/// The renderer and the workcell's drawing live in the widget's GL context: they are made when
/// the context is (initializeGL) or when a session is set, and destroyed with the context
/// current. Rendering errors never escape: lastError() keeps the last one and renderError()
/// reports it. Meshes that cannot be read (drawn from their collision triangles) are reported on
/// stderr.
class SceneView : public QOpenGLWidget {
  Q_OBJECT

 public:
  /// An empty view (nothing drawn until setSession).
  explicit SceneView(QWidget* parent = nullptr);
  ~SceneView() override;
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  /// The size the view asks for in layouts.
  void setPreferredSize(QSize size);
  /// See setPreferredSize.
  QSize sizeHint() const override;

  /// Draws `session`'s workcell from now on (nullptr: nothing); shows its initial state. The
  /// session must outlive the view or be replaced first.
  void setSession(const session::SceneSession* session);
  /// The state drawn, the contact forces drawn as arrows and what to draw.
  void showState(const rw::kinematics::State& state, std::vector<view::ContactForce> contacts,
                 const view::DrawStyle& style);
  /// Draw the contact forces (on by default).
  void setContactsVisible(bool visible);

  /// A part of what reframe() looks at: the objects' or the hand's geometry at a state.
  struct FramedPart {
    /// The state.
    rw::kinematics::State state;
    /// True: the hand's frames; false: the objects' (SceneSession::objectFrames).
    bool hand = false;
  };
  /// What reframe() looks at (setSession sets the objects in the initial state).
  void setFramed(std::vector<FramedPart> parts);
  /// Moves the camera to look at the framed parts (their bounding box with a margin) from its
  /// current direction (at the next paint, when the view has its final size).
  void reframe();
  /// Looks from `preset`'s direction at the framed parts.
  void setPreset(view::ViewPreset preset);
  /// The camera.
  const view::Orbit& orbit() const { return orbit_; }

  /// The last rendering or GL set-up error (empty: none).
  const QString& lastError() const { return lastError_; }

 signals:
  /// Rendering or GL set-up failed; `message` says why.
  void renderError(const QString& message);
  /// Space was pressed in the view (play or pause a replay).
  void playPauseRequested();

 protected:
  void initializeGL() override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  void releaseGl();
  void buildDrawing();
  void fail(const QString& message);
  void clearToBackground();
  Eigen::AlignedBox3d framedBox() const;
  int pixelWidth() const;
  int pixelHeight() const;

  QSize preferredSize_{960, 720};
  const session::SceneSession* session_ = nullptr;
  std::unique_ptr<render::GlRenderer> renderer_;
  std::unique_ptr<view::WorkcellDrawing> drawing_;
  rw::kinematics::State state_;
  std::vector<view::ContactForce> contacts_;
  view::DrawStyle style_;
  bool contactsVisible_ = true;
  std::vector<FramedPart> framed_;
  view::Orbit orbit_ = view::presetOrbit(view::ViewPreset::kOblique);
  bool framePending_ = true;
  QPoint lastMouse_;
  QString lastError_;
};

}  // namespace visgrab::viewer
