#include "visgrab/session/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "rw/common/text_file.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"

namespace visgrab::session {

namespace {

namespace fs = std::filesystem;

bool sameContent(const fs::path& a, const fs::path& b) {
  std::string ta, tb;
  return rw::common::readTextFile(a, ta).empty() && rw::common::readTextFile(b, tb).empty() &&
         ta == tb;
}

/// The folders of `databaseRoot`/hands that hold exactly one grasp description, sorted.
std::vector<fs::path> databaseHandFolders(const fs::path& databaseRoot) {
  std::vector<fs::path> folders;
  std::error_code ec;
  fs::directory_iterator it(databaseRoot / "hands", ec);
  if (ec) return folders;
  for (const auto& entry : it) {
    if (!entry.is_directory(ec)) continue;
    int descriptions = 0;
    fs::directory_iterator files(entry.path(), ec);
    if (ec) continue;
    for (const auto& file : files) {
      if (file.path().filename().string().ends_with(".grasp.xml")) ++descriptions;
    }
    if (descriptions == 1) folders.push_back(entry.path());
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

}  // namespace

rwsim::simulator::GraspTrialSetup trialSetup(const grasp::HandGraspSetup& hand,
                                             const rwsim::dynamics::DynamicWorkCell& dwc) {
  rwsim::simulator::GraspTrialSetup setup;
  setup.hand = hand.deviceName();
  setup.controller = hand.controllerName();
  setup.tcpFrame = hand.tcpFrameName();
  if (const grasp::JawFrame* jaw = hand.jawFrame()) setup.X_tcp_jaw = jaw->X_tcp_jaw;
  setup.simulator = rwsim::simulator::optionsFromEngineProperties(dwc);
  return setup;
}

void SceneLoader::setProtocol(rwsim::trial::TrialProtocol protocol) {
  protocol.requireJawFrame(hand_->jawFrame() != nullptr,
                           "the hand of " + hand_->description().file);
  protocol_ = std::move(protocol);
}

void SceneLoader::setTimeStep(std::optional<double> dt) {
  if (dt && !(std::isfinite(*dt) && *dt > 0.0)) {
    throw std::invalid_argument("the time step must be a number > 0 s");
  }
  if (dt && engine_ != "ode") {
    throw std::invalid_argument("a time step sets ODE's integration step; the " + engine_ +
                                " engine has its own");
  }
  timeStep_ = dt;
}

rw::loaders::IncludeRedirects handRedirects(const fs::path& databaseRoot,
                                            const grasp::HandGraspSetup& hand) {
  rw::loaders::IncludeRedirects redirects;
  if (hand.workcellFile().empty() || hand.dynamicsFile().empty()) return redirects;
  for (const fs::path& folder : databaseHandFolders(databaseRoot)) {
    const auto generatedWith = grasp::loadHandGraspSetup(folder);
    const fs::path& workcell = generatedWith->workcellFile();
    const fs::path& dynamics = generatedWith->dynamicsFile();
    if (sameContent(workcell, hand.workcellFile()) && sameContent(dynamics, hand.dynamicsFile())) {
      continue;
    }
    redirects[workcell] = hand.workcellFile();
    redirects[dynamics] = hand.dynamicsFile();
  }
  return redirects;
}

SceneLoader::SceneLoader(const database::Database& db, const grasp::HandGraspSetup& hand,
                         std::string engine)
    : db_(&db),
      hand_(&hand),
      engine_(std::move(engine)),
      redirects_(handRedirects(db.root(), hand)) {
  rwsim::engines::checkEngine(engine_);
}

std::unique_ptr<rwsim::dynamics::DynamicWorkCell> SceneLoader::load(
    const database::SceneEntry& entry) const {
  if (!redirects_.empty() && !fs::is_regular_file(hand_->dynamicsFile())) {
    throw std::runtime_error("the hand's dynamics file " + hand_->dynamicsFile().string() +
                             " is missing (GraspDescription dynamics=\"...\"; default: the "
                             "workcell's name up to its first dot + _dynamics.dwc.xml)");
  }
  rwsim::loaders::DynamicWorkCellLoadOptions options;
  options.includeRedirects = redirects_;
  auto dwc = rwsim::loaders::loadDynamicWorkCell(entry.dynamicWorkcell, options);
  if (!dwc->findDevice(hand_->deviceName()).valid()) {
    throw std::runtime_error("scene " + entry.id + " has no device '" + hand_->deviceName() +
                             "' and does not include the hand of its database (hands/<hand>/ "
                             "with one grasp description); cannot put the hand " +
                             hand_->description().file + " in");
  }
  return dwc;
}

}  // namespace visgrab::session
