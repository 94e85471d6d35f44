#include "visgrab/generator/settle.hpp"

#include <algorithm>
#include <stdexcept>

#include "rwsim/simulator/simulator.hpp"

namespace visgrab::generator {

SettleResult settle(const rwsim::dynamics::DynamicWorkCell& dwc,
                    const std::vector<std::string>& objects, const SettleOptions& options) {
  std::vector<rwsim::dynamics::BodyId> bodies;
  for (const std::string& name : objects) {
    const rwsim::dynamics::BodyId b = dwc.findBody(name);
    if (!b.valid() || dwc.body(b).kind != rwsim::dynamics::BodyKind::kRigid) {
      throw std::invalid_argument("settle: \"" + name + "\" is not a rigid body of the scene");
    }
    bodies.push_back(b);
  }
  rwsim::simulator::Simulator sim(dwc, rwsim::simulator::optionsFromEngineProperties(dwc));
  sim.reset(dwc.workcell().defaultState());
  SettleResult result;
  double restSince = -1.0;
  while (sim.time() < options.maxTime) {
    const auto status = sim.step();
    if (status != rwsim::simulator::StepStatus::kOk) {
      result.failure = sim.failureDetail();
      break;
    }
    bool still = true;
    result.maxSpeed = 0.0;
    for (const rwsim::dynamics::BodyId b : bodies) {
      const double v = sim.bodyLinearVelocity(b).norm();
      result.maxSpeed = std::max(result.maxSpeed, v);
      still = still && v < options.restLinearSpeed &&
              sim.bodyAngularVelocity(b).norm() < options.restAngularSpeed;
    }
    if (!still) {
      restSince = -1.0;
    } else if (restSince < 0.0) {
      restSince = sim.time();
    }
    if (sim.time() >= options.minTime && restSince >= 0.0 &&
        sim.time() - restSince >= options.restDuration) {
      result.atRest = true;
      break;
    }
  }
  result.time = sim.time();
  for (const auto& pair : sim.contacts()) {
    const bool involvesObject =
        std::find(bodies.begin(), bodies.end(), pair.bodyA) != bodies.end() ||
        std::find(bodies.begin(), bodies.end(), pair.bodyB) != bodies.end();
    if (!involvesObject) continue;
    for (const auto& c : pair.points) {
      result.maxPenetration = std::max(result.maxPenetration, c.point.depth);
    }
  }
  for (const rwsim::dynamics::BodyId b : bodies) result.X_WO.push_back(sim.bodyPose(b));
  return result;
}

}  // namespace visgrab::generator
