#include "visgrab/view/trial_replay.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>

namespace visgrab::view {

TrialReplay replayTrial(const rwsim::simulator::GraspTrial& trial,
                        const rwsim::simulator::GraspParameters& grasp,
                        const rw::kinematics::State& initial, double interval, double minForce) {
  if (!(interval > 0.0)) throw std::invalid_argument("replayTrial: the interval must be > 0");
  TrialReplay replay;
  replay.frames.push_back(ReplayFrame{0.0, "placed", trial.placedState(grasp, initial), {}});

  // The newest step, kept until it is known whether it is the last of its phase.
  std::optional<ReplayFrame> latest;
  bool latestKept = false;
  double nextSample = interval;
  auto keepLatest = [&] {
    if (latest && !latestKept) {
      replay.frames.push_back(*latest);
      latestKept = true;
    }
  };
  auto contactsOf = [&](const rwsim::trial::PhysicsEngine& sim) {
    std::vector<ContactForce> out;
    for (const auto& pair : sim.contacts()) {
      const bool handA = trial.isHandBody(pair.bodyA);
      const bool handB = trial.isHandBody(pair.bodyB);
      if (handA == handB) continue;
      for (const auto& p : pair.points) {
        if (p.force.norm() < minForce) continue;
        // SolvedContact::force acts on B from A.
        out.push_back(handA ? ContactForce{p.point.position, p.force, pair.bodyB}
                            : ContactForce{p.point.position, -p.force, pair.bodyA});
      }
    }
    return out;
  };

  const rwsim::simulator::Observer observer = [&](const rwsim::trial::PhysicsEngine& sim,
                                                  std::string_view phase) {
    const bool phaseChanged = latest && latest->phase != phase;
    if (phaseChanged && latest->phase == "close") {
      keepLatest();
      replay.closed = replay.frames.size() - 1;
    }
    latest = ReplayFrame{sim.time(), std::string(phase), sim.state(), contactsOf(sim)};
    latestKept = false;
    if (sim.time() + 1e-9 >= nextSample) {
      keepLatest();
      nextSample = (std::floor(sim.time() / interval + 1e-6) + 1.0) * interval;
    }
  };
  replay.result = trial.run(grasp, initial, observer);
  if (latest && latest->phase == "close") {
    keepLatest();
    replay.closed = replay.frames.size() - 1;
  }
  keepLatest();
  replay.lifted = replay.frames.size() - 1;
  if (replay.closed == 0) replay.closed = replay.lifted;
  return replay;
}

bool replayDiffers(const results::TrialRecord& record,
                   const rwsim::simulator::GraspTrialResult& replayed) {
  return record.outcome != replayed.outcome || record.simulatedTime != replayed.simulatedTime;
}

}  // namespace visgrab::view
