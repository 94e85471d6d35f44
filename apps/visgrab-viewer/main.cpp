// visgrab-viewer: browse a database's scenes, their grasps and outcomes, replay a grasp's trial
// in a QOpenGLWidget over the project's renderer (docs/viewer.md).
#include <QApplication>
#include <QElapsedTimer>
#include <QImage>
#include <QSurfaceFormat>
#include <QThread>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "scene_view.hpp"
#include "viewer_options.hpp"
#include "viewer_window.hpp"
#include "visgrab/session/grasp_order.hpp"

namespace {

using visgrab::viewer::ViewerOptions;
using visgrab::viewer::ViewerWindow;

constexpr int kScreenshotTimeoutMs = 20000;

// OpenGL 3.3 core with a depth buffer (GlRenderer::draw needs one) and 4x anti-aliasing, for
// every context Qt makes; set before the QApplication exists.
void setDefaultSurfaceFormat() {
  QSurfaceFormat format;
  format.setRenderableType(QSurfaceFormat::OpenGL);
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  format.setStencilBufferSize(8);
  format.setSamples(4);
  QSurfaceFormat::setDefaultFormat(format);
}

// The scene and grasp asked for exist (checked before any window opens).
// @throws database::UnknownSceneError, std::invalid_argument naming the choices.
void checkStartSelection(const visgrab::viewer::ViewerData& data, const ViewerOptions& options) {
  if (!options.scene) return;
  const visgrab::database::SceneEntry& entry = data.database->scene(*options.scene);
  if (!options.grasp) return;
  const auto grasps = visgrab::session::sceneGrasps(*data.database, entry, data.grasps,
                                                    data.results ? &*data.results : nullptr);
  try {
    visgrab::session::selectGrasp(grasps, *options.grasp, options.method);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--grasp " + *options.grasp + ": " + e.what());
  }
}

// True when Qt has somewhere to open a window (without one, QApplication aborts).
bool haveDisplay() {
  for (const char* name : {"QT_QPA_PLATFORM", "DISPLAY", "WAYLAND_DISPLAY"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && *value != '\0') return true;
  }
  return false;
}

// Shows the window, renders the 3-D view once and saves it. Returns the exit code.
int saveScreenshot(ViewerWindow& window, const ViewerOptions& options) {
  window.show();
  // The view gets its context once the window is exposed.
  QElapsedTimer clock;
  clock.start();
  while (!window.sceneView().isValid() && clock.elapsed() < kScreenshotTimeoutMs) {
    QApplication::processEvents(QEventLoop::AllEvents, 50);
    if (!window.sceneView().isValid()) QThread::msleep(10);
  }
  if (!window.sceneView().isValid()) {
    std::cerr << "visgrab-viewer: error: the 3-D view got no OpenGL context (is there a display? "
                 "try xvfb-run)\n";
    return 1;
  }
  QApplication::processEvents();
  const QImage image = window.sceneView().grabFramebuffer();
  if (!window.sceneView().lastError().isEmpty()) {
    std::cerr << "visgrab-viewer: error: " << window.sceneView().lastError().toStdString() << "\n";
    return 1;
  }
  const std::string file = options.screenshot->string();
  if (image.isNull() || !image.save(QString::fromStdString(file), "PNG")) {
    std::cerr << "visgrab-viewer: error: cannot write the screenshot " << file << "\n";
    return 1;
  }
  std::cout << "screenshot " << image.width() << "x" << image.height() << " in " << file << "\n";
  return 0;
}

int run(int argc, char** argv) {
  ViewerOptions options;
  try {
    options = visgrab::viewer::parseViewerOptions(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const visgrab::viewer::UsageError& e) {
    std::cerr << "visgrab-viewer: " << e.what() << "\n" << visgrab::viewer::usageLine();
    return 2;
  }
  if (options.help) {
    std::cout << options.helpText;
    return 0;
  }
  visgrab::viewer::ViewerData data;
  try {
    data = visgrab::viewer::loadViewerData(options);
  } catch (const visgrab::viewer::UsageError& e) {
    std::cerr << "visgrab-viewer: " << e.what() << "\n" << visgrab::viewer::usageLine();
    return 2;
  } catch (const rw::common::LoadError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  for (const auto& w : data.warnings) std::cerr << w << "\n";
  checkStartSelection(data, options);
  if (!data.replayProblem.empty()) {
    // No replay with another protocol than the run's: --grasp is refused, the window replays
    // nothing.
    if (options.grasp) {
      std::cerr << "visgrab-viewer: error: cannot replay --grasp " << *options.grasp << ": "
                << data.replayProblem << "\n";
      return 1;
    }
    std::cerr << "visgrab-viewer: trials are not replayed: " << data.replayProblem << "\n";
  }
  if (!haveDisplay()) {
    std::cerr << "visgrab-viewer: error: no display: set DISPLAY (or QT_QPA_PLATFORM), or run "
                 "under xvfb-run\n";
    return 1;
  }

  setDefaultSurfaceFormat();
  // Qt sees no arguments of ours (they were checked above); its own settings come from the
  // environment (QT_QPA_PLATFORM, DISPLAY, ...).
  int qtArgc = 1;
  char* qtArgv[] = {argv[0], nullptr};
  QApplication app(qtArgc, qtArgv);
  QApplication::setApplicationName("visgrab-viewer");

  ViewerWindow window(std::move(data), options);
  window.openScene(options.scene.value_or(""));
  if (options.grasp) {
    const QString problem = window.openGrasp(*options.grasp, options.method);
    if (!problem.isEmpty()) std::cerr << "visgrab-viewer: " << problem.toStdString() << "\n";
    if (!window.replayOutcome().isEmpty()) {
      std::cout << "grasp " << *options.grasp << ": " << window.replayOutcome().toStdString()
                << "\n";
    }
    if (!window.replayNote().isEmpty()) {
      std::cerr << "visgrab-viewer: grasp " << *options.grasp << ": "
                << window.replayNote().toStdString() << "\n";
    }
    window.showMoment(ViewerWindow::Moment::kLifted);
  }
  if (options.screenshot) return saveScreenshot(window, options);
  window.show();
  return QApplication::exec();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const rw::common::LoadError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "visgrab-viewer: error: " << e.what() << "\n";
    return 1;
  }
}
