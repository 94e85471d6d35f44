#include "scene_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <numbers>
#include <utility>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QWheelEvent>

#include "visgrab/render/scene.hpp"
#include "visgrab/render/srgb.hpp"
#include "visgrab/view/grasp_pictures.hpp"

namespace visgrab::viewer {

namespace {

constexpr double kDegreesPerPixel = 0.4;
constexpr double kZoomPerWheelUnit = 0.9985;  // 120 units a notch: about 17 % closer
constexpr double kMinDistance = 0.01;
constexpr double kMaxDistance = 100.0;
constexpr double kMetresPerNewton = 0.01;  // as the pictures (view::PictureOptions)
constexpr double kFramingMargin = 0.03;    // m around what is framed

QString glVersionText(const QOpenGLContext* context) {
  if (context == nullptr) return "no OpenGL context";
  const auto version = context->format().version();
  return QString("OpenGL %1.%2 %3 context")
      .arg(version.first)
      .arg(version.second)
      .arg(context->format().profile() == QSurfaceFormat::CoreProfile ? "core" : "compatibility");
}

}  // namespace

SceneView::SceneView(QWidget* parent) : QOpenGLWidget(parent) {
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(160, 120);
}

SceneView::~SceneView() {
  // The context outlives this destructor; its aboutToBeDestroyed must not reach a half-destroyed
  // view, so the GL objects go now.
  if (context() != nullptr) disconnect(context(), nullptr, this, nullptr);
  releaseGl();
}

void SceneView::setPreferredSize(QSize size) {
  preferredSize_ = size;
  updateGeometry();
}

QSize SceneView::sizeHint() const { return preferredSize_; }

void SceneView::setSession(const session::SceneSession* session) {
  session_ = session;
  state_ = session != nullptr ? session->initialState() : rw::kinematics::State();
  contacts_.clear();
  style_ = view::DrawStyle{};
  framed_.clear();
  if (session != nullptr) framed_.push_back(FramedPart{state_, false});
  framePending_ = true;
  if (isValid()) {
    makeCurrent();
    buildDrawing();
    doneCurrent();
  }
  update();
}

void SceneView::showState(const rw::kinematics::State& state,
                          std::vector<view::ContactForce> contacts, const view::DrawStyle& style) {
  state_ = state;
  contacts_ = std::move(contacts);
  style_ = style;
  update();
}

void SceneView::setContactsVisible(bool visible) {
  contactsVisible_ = visible;
  update();
}

void SceneView::setFramed(std::vector<FramedPart> parts) { framed_ = std::move(parts); }

Eigen::AlignedBox3d SceneView::framedBox() const {
  Eigen::AlignedBox3d box;
  for (const FramedPart& part : framed_) {
    box.extend(drawing_->bounds(part.state,
                                part.hand ? drawing_->handFrames() : session_->objectFrames()));
  }
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  box.min().array() -= kFramingMargin;
  box.max().array() += kFramingMargin;
  return box;
}

void SceneView::reframe() {
  // Framed at the next paint, when the view has its final size.
  framePending_ = true;
  update();
}

void SceneView::setPreset(view::ViewPreset preset) {
  const view::Orbit p = view::presetOrbit(preset);
  orbit_.azimuthDeg = p.azimuthDeg;
  orbit_.elevationDeg = p.elevationDeg;
  reframe();
}

void SceneView::initializeGL() {
  connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &SceneView::releaseGl);
  try {
    renderer_ = std::make_unique<render::GlRenderer>();
  } catch (const std::exception& e) {
    fail(QString("cannot draw with the %1: %2").arg(glVersionText(context()), e.what()));
    return;
  }
  buildDrawing();
}

void SceneView::buildDrawing() {
  drawing_.reset();
  if (session_ == nullptr) return;
  try {
    // A fresh renderer per workcell, so the previous scene's meshes are freed with it.
    if (!renderer_ || renderer_->meshCount() > 0) {
      renderer_.reset();
      renderer_ = std::make_unique<render::GlRenderer>();
    }
    drawing_ = std::make_unique<view::WorkcellDrawing>(session_->workcell(), *renderer_,
                                                       session_->hand().deviceName());
    for (const std::string& w : drawing_->warnings()) {
      std::fprintf(stderr, "visgrab-viewer: warning: %s\n", w.c_str());
    }
  } catch (const std::exception& e) {
    drawing_.reset();
    fail(QString("cannot upload the scene's meshes: %1").arg(e.what()));
  }
}

void SceneView::releaseGl() {
  if (!renderer_ && !drawing_) return;
  makeCurrent();
  drawing_.reset();
  renderer_.reset();
  doneCurrent();
}

void SceneView::fail(const QString& message) {
  const bool changed = message != lastError_;
  lastError_ = message;
  if (changed) emit renderError(message);
}

void SceneView::clearToBackground() {
  QOpenGLFunctions* gl = context()->functions();
  const Eigen::Vector3f b = view::studioBackground();
  gl->glClearColor(render::encodeSrgb(b.x()), render::encodeSrgb(b.y()), render::encodeSrgb(b.z()),
                   1.0f);
  gl->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

int SceneView::pixelWidth() const {
  return std::max(1, static_cast<int>(std::lround(width() * devicePixelRatioF())));
}

int SceneView::pixelHeight() const {
  return std::max(1, static_cast<int>(std::lround(height() * devicePixelRatioF())));
}

void SceneView::paintGL() {
  if (!drawing_ || state_.values().empty()) {
    clearToBackground();
    return;
  }
  if (framePending_) {
    orbit_ = view::framed(orbit_, framedBox(), pixelWidth(), pixelHeight());
    framePending_ = false;
  }
  try {
    render::Scene scene;
    scene.lighting = view::studioLighting();
    scene.background = view::studioBackground();
    drawing_->addItems(state_, scene, style_);
    if (contactsVisible_) view::addContactArrows(*drawing_, contacts_, kMetresPerNewton, scene);
    renderer_->draw(scene, view::orbitCamera(orbit_, pixelWidth(), pixelHeight()));
    lastError_.clear();
  } catch (const std::exception& e) {
    clearToBackground();
    fail(QString("drawing failed: %1").arg(e.what()));
  }
}

void SceneView::mousePressEvent(QMouseEvent* event) {
  lastMouse_ = event->pos();
  event->accept();
}

void SceneView::mouseMoveEvent(QMouseEvent* event) {
  const QPoint delta = event->pos() - lastMouse_;
  lastMouse_ = event->pos();
  if (event->buttons() & Qt::LeftButton) {
    // Grab and turn: dragging right turns the scene right, dragging down tips it towards you.
    orbit_.azimuthDeg -= kDegreesPerPixel * delta.x();
    orbit_.elevationDeg =
        std::clamp(orbit_.elevationDeg + kDegreesPerPixel * delta.y(), -89.5, 89.5);
    orbit_.azimuthDeg = std::remainder(orbit_.azimuthDeg, 360.0);
  } else if (event->buttons() & (Qt::RightButton | Qt::MiddleButton)) {
    // Grab and move: the point under the mouse follows it (at the target's depth).
    const double metresPerPixel = 2.0 * orbit_.distance *
                                  std::tan(orbit_.fovYDeg * std::numbers::pi / 360.0) /
                                  std::max(1, height());
    const rw::math::Transform3D X_WC = view::orbitCamera(orbit_, pixelWidth(), pixelHeight()).X_WC;
    orbit_.target -=
        metresPerPixel * (delta.x() * X_WC.linear().col(0) + delta.y() * X_WC.linear().col(1));
  } else {
    return;
  }
  update();
  event->accept();
}

void SceneView::mouseDoubleClickEvent(QMouseEvent* event) {
  reframe();
  event->accept();
}

void SceneView::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y();
  orbit_.distance =
      std::clamp(orbit_.distance * std::pow(kZoomPerWheelUnit, steps), kMinDistance, kMaxDistance);
  update();
  event->accept();
}

void SceneView::keyPressEvent(QKeyEvent* event) {
  switch (event->key()) {
    case Qt::Key_F:
      reframe();
      break;
    case Qt::Key_1:
      setPreset(view::ViewPreset::kOblique);
      break;
    case Qt::Key_2:
      setPreset(view::ViewPreset::kFront);
      break;
    case Qt::Key_3:
      setPreset(view::ViewPreset::kSide);
      break;
    case Qt::Key_4:
      setPreset(view::ViewPreset::kTop);
      break;
    case Qt::Key_Space:
      emit playPauseRequested();
      break;
    default:
      QOpenGLWidget::keyPressEvent(event);
      return;
  }
  event->accept();
}

}  // namespace visgrab::viewer
