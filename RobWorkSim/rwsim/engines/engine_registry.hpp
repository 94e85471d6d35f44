#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rwsim/dynamics/dynamic_workcell.hpp"
#include "rwsim/trial/physics_engine.hpp"
#include "rwsim/trial/trial_types.hpp"

/// The physics engines of this build, by the names `visgrab run --engine` takes.
namespace rwsim::engines {

/// The benchmark's engine.
inline constexpr std::string_view kDefaultEngine = "ode";

/// Every engine name the project knows ("ode", "mujoco"), built or not.
std::vector<std::string> knownEngines();
/// The engines this build has: "ode", and "mujoco" when it was configured with MuJoCo.
std::vector<std::string> availableEngines();
/// Whether this build has the engine `name`.
bool isAvailable(std::string_view name);
/// @throws std::invalid_argument for a name that is no engine (listing the known ones) or an
/// engine this build lacks (saying how to get it: for MuJoCo, Debian's libmujoco-dev and a new
/// configure).
void checkEngine(std::string_view name);
/// The factory a GraspTrial on `dwc` with `setup` runs `name`'s engine with; null for "ode"
/// (GraspTrial then makes ODE engines itself, with setup.simulator and the contact detector it
/// shares between its trials). @throws std::invalid_argument as checkEngine, or naming the frame
/// and the reason when the engine cannot take the dwc.
std::shared_ptr<const trial::EngineFactory> engineFactory(std::string_view name,
                                                          const dynamics::DynamicWorkCell& dwc,
                                                          const trial::GraspTrialSetup& setup);

}  // namespace rwsim::engines
