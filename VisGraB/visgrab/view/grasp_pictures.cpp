#include "visgrab/view/grasp_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rw/common/number_text.hpp"
#include "visgrab/analysis/report.hpp"
#include "visgrab/render/srgb.hpp"

namespace visgrab::view {

namespace {

using rwsim::trial::GraspOutcome;

constexpr int kCaptionHeight = 30;
constexpr int kTitleHeight = 36;
const cv::Scalar kCaptionBackground(250, 250, 250);
const cv::Scalar kInk(30, 30, 30);

/// The report's colour of an outcome as 8-bit sRGB.
cv::Scalar outcomeInk(GraspOutcome outcome) {
  const std::string_view hex = analysis::outcomeColour(outcome);
  unsigned r = 0, g = 0, b = 0;
  if (hex.size() == 7) std::sscanf(std::string(hex).c_str(), "#%02x%02x%02x", &r, &g, &b);
  return cv::Scalar(r, g, b);
}

cv::Mat toMat(const visual::RgbImage& image) {
  cv::Mat mat(image.height, image.width, CV_8UC3);
  std::copy(image.pixels.begin(), image.pixels.end(), mat.data);
  return mat;
}

visual::RgbImage fromMat(const cv::Mat& mat) {
  visual::RgbImage image;
  image.width = mat.cols;
  image.height = mat.rows;
  const cv::Mat c = mat.isContinuous() ? mat : mat.clone();
  image.pixels.assign(c.data, c.data + c.total() * c.elemSize());
  return image;
}

/// A bar of `height` x `width` with `text` at its left; `accent` (if any) after it in colour.
cv::Mat textBar(int width, int height, const std::string& text, double scale,
                const std::string& accent = {}, cv::Scalar accentColour = kInk) {
  cv::Mat bar(height, width, CV_8UC3, kCaptionBackground);
  int baseline = 0;
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const cv::Size size = cv::getTextSize(text, font, scale, 1, &baseline);
  const int y = (height + size.height) / 2;
  cv::putText(bar, text, cv::Point(8, y), font, scale, kInk, 1, cv::LINE_AA);
  if (!accent.empty()) {
    const int x = 8 + size.width + 14;
    cv::rectangle(bar, cv::Rect(x, y - size.height, size.height, size.height), accentColour,
                  cv::FILLED);
    cv::putText(bar, accent, cv::Point(x + size.height + 6, y), font, scale, kInk, 1, cv::LINE_AA);
  }
  return bar;
}

/// `image` over a caption bar.
cv::Mat captioned(const cv::Mat& image, const std::string& caption) {
  cv::Mat out;
  cv::vconcat(image, textBar(image.cols, kCaptionHeight, caption, 0.5), out);
  return out;
}

/// A title bar over `body`: `title`, then the outcome with its colour swatch.
cv::Mat titled(const cv::Mat& body, const std::string& title, const std::string& accent,
               cv::Scalar accentColour) {
  cv::Mat out;
  cv::vconcat(textBar(body.cols, kTitleHeight, title, 0.55, accent, accentColour), body, out);
  return out;
}

/// A 1-pixel grey border around an image (panels and tiles stay apart).
cv::Mat framedPanel(const cv::Mat& panel) {
  cv::Mat out;
  cv::copyMakeBorder(panel, out, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(160, 160, 160));
  return out;
}

std::string timeCaption(const char* what, double t) {
  char text[64];
  std::snprintf(text, sizeof text, "%s   t = %.2f s", what, t);
  return text;
}

}  // namespace

Eigen::Vector3f outcomeColour(GraspOutcome outcome) {
  const cv::Scalar ink = outcomeInk(outcome);
  return Eigen::Vector3f(render::decodeSrgb(static_cast<float>(ink[0] / 255.0)),
                         render::decodeSrgb(static_cast<float>(ink[1] / 255.0)),
                         render::decodeSrgb(static_cast<float>(ink[2] / 255.0)));
}

std::string outcomeCaption(GraspOutcome outcome, double qLift, double qGws, double qGwsUnit) {
  std::string text(rwsim::trial::outcomeName(outcome));
  if (outcome == GraspOutcome::kStable || outcome == GraspOutcome::kSlipped) {
    const auto value = [](const char* name, double q, int digits) {
      if (std::isnan(q)) return "   " + std::string(name) + " -";  // ASCII: drawn by OpenCV
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "   %s %.*f", name, digits, q);
      return std::string(buffer);
    };
    text += value("Q_lift", qLift, 3) + value("Q_GWS", qGws, 4) + value("Q_GWS,unit", qGwsUnit, 4);
  }
  return text;
}

Eigen::AlignedBox3d objectsBox(const session::SceneSession& session, const WorkcellDrawing& drawing,
                               const rw::kinematics::State& state, double margin) {
  Eigen::AlignedBox3d box = drawing.bounds(state, session.objectFrames());
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  box.min().array() -= margin;
  box.max().array() += margin;
  return box;
}

void addContactArrows(const WorkcellDrawing& drawing, const std::vector<ContactForce>& contacts,
                      double metresPerNewton, render::Scene& scene) {
  const Eigen::Vector3f orange(1.0f, 0.55f, 0.0f);
  for (const ContactForce& c : contacts) {
    const double f = c.force.norm();
    if (!(f > 0.0)) continue;
    const double length = std::clamp(f * metresPerNewton, 0.01, 0.06);
    const Eigen::Vector3d dir = c.force / f;
    drawing.addArrow(c.point - length * dir, c.point, 0.0025, orange, scene);
  }
}

visual::RgbImage renderState(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                             const rw::kinematics::State& state,
                             const std::vector<ContactForce>& contacts, const DrawStyle& style,
                             const Orbit& orbit, const PictureOptions& options) {
  render::Scene scene;
  scene.lighting = studioLighting();
  scene.background = studioBackground();
  drawing.addItems(state, scene, style);
  if (options.contacts) addContactArrows(drawing, contacts, options.metresPerNewton, scene);
  render::RenderOptions ro;
  ro.colourSamples = options.samples;
  return renderer.render(scene, orbitCamera(orbit, options.width, options.height), ro).colour;
}

visual::RgbImage graspStrip(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                            const session::SceneSession& session, const TrialReplay& replay,
                            const std::string& title, const PictureOptions& options) {
  const auto& placed = replay.frames.at(replay.placed);
  const auto& closed = replay.frames.at(replay.closed);
  const auto& lifted = replay.frames.at(replay.lifted);
  // One camera for the three panels: the grasped object (all objects when none was touched)
  // at the start, the hand placed and lifted.
  Eigen::AlignedBox3d box;
  const rwsim::dynamics::BodyId object = replay.result.object;
  const auto& dwc = session.dynamicWorkcell();
  if (object.valid() && object.index() < dwc.bodies().size()) {
    box = drawing.bounds(placed.state, dwc.body(object).geometryFrames);
  }
  if (box.isEmpty()) box = objectsBox(session, drawing, placed.state);
  const auto hand = drawing.handFrames();
  box.extend(drawing.bounds(placed.state, hand));
  box.extend(drawing.bounds(lifted.state, hand));
  const Orbit orbit = framed(presetOrbit(options.view), box, options.width, options.height);
  const DrawStyle style;
  const bool simulated = replay.frames.size() > 1;
  std::vector<cv::Mat> panels;
  panels.push_back(
      captioned(toMat(renderState(renderer, drawing, placed.state, {}, style, orbit, options)),
                timeCaption("1  placed, before closing", placed.time)));
  if (simulated) {
    panels.push_back(captioned(
        toMat(renderState(renderer, drawing, closed.state, closed.contacts, style, orbit, options)),
        timeCaption("2  fingers closed", closed.time)));
    const char* last = lifted.phase == "close" ? "3  stopped while closing" : "3  after lifting";
    panels.push_back(captioned(
        toMat(renderState(renderer, drawing, lifted.state, lifted.contacts, style, orbit, options)),
        timeCaption(last, lifted.time)));
  }
  for (auto& p : panels) p = framedPanel(p);
  cv::Mat strip;
  cv::hconcat(panels, strip);
  const auto& r = replay.result;
  return fromMat(titled(strip, title, outcomeCaption(r.outcome, r.qLift, r.qGws, r.qGwsUnit),
                        outcomeInk(r.outcome)));
}

visual::RgbImage graspMontage(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                              const session::SceneSession& session,
                              const std::vector<MontageTile>& tiles, const std::string& title,
                              const PictureOptions& options, int columns) {
  columns = std::max(1, columns);
  const rw::kinematics::State& initial = session.initialState();
  std::vector<cv::Mat> cells;

  // Overview: every grasp's approach, 8 cm long, ending at its TCP.
  {
    render::Scene scene;
    scene.lighting = studioLighting();
    scene.background = studioBackground();
    drawing.addItems(initial, scene, DrawStyle{false, true, std::nullopt});
    Eigen::AlignedBox3d box = objectsBox(session, drawing, initial, 0.03);
    for (const MontageTile& t : tiles) {
      if (!t.grasp) continue;
      const Eigen::Vector3d tcp = t.grasp->X_W_tcp.translation();
      const Eigen::Vector3d approach = t.grasp->X_W_tcp.linear().col(2);
      drawing.addArrow(tcp - 0.08 * approach, tcp, 0.002, outcomeColour(t.outcome), scene);
      box.extend(tcp - 0.08 * approach);
    }
    render::RenderOptions ro;
    ro.colourSamples = options.samples;
    const Orbit orbit = framed(presetOrbit(options.view), box, options.width, options.height);
    cells.push_back(captioned(
        toMat(renderer.render(scene, orbitCamera(orbit, options.width, options.height), ro).colour),
        "all " + std::to_string(tiles.size()) + " grasps: approach to TCP"));
  }
  for (const MontageTile& t : tiles) {
    cv::Mat image;
    if (t.grasp) {
      const rw::kinematics::State placed = session.trial().placedState(*t.grasp, initial);
      Eigen::AlignedBox3d box = objectsBox(session, drawing, initial);
      box.extend(drawing.bounds(placed, drawing.handFrames()));
      const Orbit orbit = framed(presetOrbit(options.view), box, options.width, options.height);
      DrawStyle style;
      style.handColour = outcomeColour(t.outcome);
      image = toMat(renderState(renderer, drawing, placed, {}, style, orbit, options));
    } else {
      const Orbit orbit = framed(presetOrbit(options.view), objectsBox(session, drawing, initial),
                                 options.width, options.height);
      image = toMat(
          renderState(renderer, drawing, initial, {}, DrawStyle{false, true, {}}, orbit, options));
      cv::putText(image, "no hand pose", cv::Point(10, 30), cv::FONT_HERSHEY_SIMPLEX, 0.7, kInk, 1,
                  cv::LINE_AA);
    }
    // The outcome's colour as a band along the tile's top edge.
    cv::rectangle(image, cv::Rect(0, 0, image.cols, 6), outcomeInk(t.outcome), cv::FILLED);
    cells.push_back(
        captioned(image, t.label + "  " + std::string(rwsim::trial::outcomeName(t.outcome))));
  }
  for (auto& c : cells) c = framedPanel(c);
  const cv::Mat blank(cells.front().rows, cells.front().cols, CV_8UC3, kCaptionBackground);
  std::vector<cv::Mat> rows;
  for (std::size_t i = 0; i < cells.size(); i += static_cast<std::size_t>(columns)) {
    std::vector<cv::Mat> row;
    for (std::size_t j = i; j < i + static_cast<std::size_t>(columns); ++j) {
      row.push_back(j < cells.size() ? cells[j] : blank);
    }
    cv::Mat joined;
    cv::hconcat(row, joined);
    rows.push_back(joined);
  }
  cv::Mat grid;
  cv::vconcat(rows, grid);

  // Legend: the outcomes present, in the report's order.
  std::set<int> present;
  for (const MontageTile& t : tiles) present.insert(static_cast<int>(t.outcome));
  cv::Mat legend(kCaptionHeight, grid.cols, CV_8UC3, kCaptionBackground);
  int x = 8;
  for (const int o : present) {
    const auto outcome = static_cast<GraspOutcome>(o);
    const std::string name(rwsim::trial::outcomeName(outcome));
    cv::rectangle(legend, cv::Rect(x, 9, 12, 12), outcomeInk(outcome), cv::FILLED);
    cv::putText(legend, name, cv::Point(x + 18, 20), cv::FONT_HERSHEY_SIMPLEX, 0.45, kInk, 1,
                cv::LINE_AA);
    int baseline = 0;
    x += 18 + cv::getTextSize(name, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline).width + 20;
  }
  cv::Mat out;
  cv::vconcat(grid, legend, out);
  return fromMat(titled(out, title, {}, kInk));
}

visual::RgbImage graspOverlay(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                              const rw::kinematics::State& placed,
                              const rw::math::Transform3D& X_W_tcp, const visual::RgbImage& left,
                              const database::StereoCalibration& calibration, GraspOutcome outcome,
                              const std::string& title) {
  if (left.width != calibration.width || left.height != calibration.height) {
    throw std::invalid_argument("graspOverlay: the left image is " + std::to_string(left.width) +
                                "x" + std::to_string(left.height) + " but the calibration is for " +
                                std::to_string(calibration.width) + "x" +
                                std::to_string(calibration.height));
  }
  render::PinholeCamera camera;
  camera.fx = calibration.K1(0, 0);
  camera.fy = calibration.K1(1, 1);
  camera.cx = calibration.K1(0, 2);
  camera.cy = calibration.K1(1, 2);
  camera.skew = calibration.K1(0, 1);
  camera.width = calibration.width;
  camera.height = calibration.height;
  camera.near = 0.02;
  camera.far = 20.0;
  camera.X_WC = calibration.X_TL;

  render::Scene all;
  drawing.addItems(placed, all);
  render::Scene handOnly;
  drawing.addItems(placed, handOnly, DrawStyle{true, false, std::nullopt});
  render::RenderOptions ro;
  ro.colourSamples = 1;
  const auto visibleIds = renderer.render(all, camera, ro).instanceIds;
  const auto handIds = renderer.render(handOnly, camera, ro).instanceIds;

  cv::Mat image = toMat(left);
  const cv::Scalar ink = outcomeInk(outcome);
  cv::Mat mask(image.rows, image.cols, CV_8U, cv::Scalar(0));
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      if (handIds.at(r, c) == 0) continue;
      mask.at<std::uint8_t>(r, c) = 255;
      const double alpha = drawing.isHandInstance(visibleIds.at(r, c)) ? 0.6 : 0.25;
      auto& px = image.at<cv::Vec3b>(r, c);
      for (int k = 0; k < 3; ++k) {
        px[k] = cv::saturate_cast<std::uint8_t>((1.0 - alpha) * px[k] + alpha * ink[k]);
      }
    }
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(image, contours, -1, ink, 2, cv::LINE_AA);
  // The approach: 10 cm towards the TCP, where both ends are in front of the camera.
  const Eigen::Vector3d tcp = X_W_tcp.translation();
  const Eigen::Vector3d from = tcp - 0.10 * X_W_tcp.linear().col(2);
  const Eigen::Isometry3d X_CW = camera.X_WC.inverse();
  if ((X_CW * tcp).z() > camera.near && (X_CW * from).z() > camera.near) {
    const Eigen::Vector2d a = camera.project(from);
    const Eigen::Vector2d b = camera.project(tcp);
    cv::arrowedLine(image, cv::Point2d(a.x(), a.y()), cv::Point2d(b.x(), b.y()),
                    cv::Scalar(255, 255, 255), 3, cv::LINE_AA, 0, 0.2);
    cv::arrowedLine(image, cv::Point2d(a.x(), a.y()), cv::Point2d(b.x(), b.y()), ink, 1,
                    cv::LINE_AA, 0, 0.2);
  }
  return fromMat(titled(image, title, std::string(rwsim::trial::outcomeName(outcome)), ink));
}

TrialPicture trialStrip(render::GlRenderer& renderer, const WorkcellDrawing& drawing,
                        const session::SceneSession& session, const session::SceneGrasp& grasp,
                        const PictureOptions& options) {
  const std::string title =
      session.entry().id + "   " + grasp.request.method + " " + grasp.request.id;
  TrialPicture picture;
  const grasp::ResolvedGrasp resolved = session.resolve(grasp.request);
  if (resolved.status == grasp::ResolveStatus::kInputError) {
    throw std::invalid_argument("grasp " + grasp.request.id + " (" + grasp.request.method +
                                ") is not valid for this hand: " + resolved.message);
  }
  if (!resolved.placed()) {
    picture.outcome = GraspOutcome::kInvalidContacts;
    picture.note = "the grasp cannot be placed: " + resolved.message;
    const rw::kinematics::State& initial = session.initialState();
    const Orbit orbit = framed(presetOrbit(options.view), objectsBox(session, drawing, initial),
                               options.width, options.height);
    cv::Mat panel =
        captioned(toMat(renderState(renderer, drawing, initial, {},
                                    DrawStyle{false, true, std::nullopt}, orbit, options)),
                  "no hand pose: the contact IK found none");
    picture.image =
        fromMat(titled(framedPanel(panel), title, "invalid_contacts", outcomeInk(picture.outcome)));
    return picture;
  }
  const TrialReplay replay =
      replayTrial(session.trial(), resolved.parameters, session.initialState());
  picture.outcome = replay.result.outcome;
  if (grasp.record && replayDiffers(*grasp.record, replay.result)) {
    const auto said = [](GraspOutcome outcome, double time) {
      return std::string(rwsim::trial::outcomeName(outcome)) + " after " +
             rw::common::shortestText(time) + " s";
    };
    picture.note = "replayed as " + said(picture.outcome, replay.result.simulatedTime) +
                   " but the results say " +
                   said(grasp.record->outcome, grasp.record->simulatedTime) +
                   " (another build, hand, database or protocol than the run's?)";
  }
  picture.image = graspStrip(renderer, drawing, session, replay, title, options);
  return picture;
}

}  // namespace visgrab::view
