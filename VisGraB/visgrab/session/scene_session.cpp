#include "visgrab/session/scene_session.hpp"

#include <utility>

namespace visgrab::session {

SceneSession::SceneSession(const SceneLoader& loader, const database::SceneEntry& entry)
    : entry_(entry), hand_(&loader.hand()) {
  dwc_ = loader.load(entry);
  rwsim::simulator::GraspTrialSetup setup = trialSetup(*hand_, *dwc_);
  if (loader.timeStep()) setup.simulator.timeStep = *loader.timeStep();
  setup.protocol = loader.protocol();
  auto engine = rwsim::engines::engineFactory(loader.engine(), *dwc_, setup);
  trial_ =
      std::make_unique<rwsim::simulator::GraspTrial>(*dwc_, std::move(setup), std::move(engine));
  initial_ = dwc_->workcell().defaultState();
  const auto& bodies = dwc_->bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].kind != rwsim::dynamics::BodyKind::kRigid) continue;
    if (trial_->isHandBody(rwsim::dynamics::BodyId(b))) continue;
    for (const auto frame : bodies[b].geometryFrames) objectFrames_.push_back(frame);
  }
}

grasp::ResolvedGrasp SceneSession::resolve(const grasp::GraspRequest& request) const {
  return grasp::resolve(request, *hand_, [this](const rwsim::simulator::GraspParameters& g) {
    return trial_->checkPlacement(g, initial_);
  });
}

}  // namespace visgrab::session
