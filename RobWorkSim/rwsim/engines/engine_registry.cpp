#include "rwsim/engines/engine_registry.hpp"

#include <stdexcept>

#ifdef VISGRAB_WITH_MUJOCO
#include "rwsim/mujoco/mujoco_engine.hpp"
#endif

namespace rwsim::engines {

namespace {

constexpr std::string_view kMujoco = "mujoco";

}  // namespace

std::vector<std::string> knownEngines() {
  return {std::string(kDefaultEngine), std::string(kMujoco)};
}

std::vector<std::string> availableEngines() {
  std::vector<std::string> out{std::string(kDefaultEngine)};
#ifdef VISGRAB_WITH_MUJOCO
  out.emplace_back(kMujoco);
#endif
  return out;
}

bool isAvailable(std::string_view name) {
  for (const std::string& e : availableEngines()) {
    if (e == name) return true;
  }
  return false;
}

void checkEngine(std::string_view name) {
  if (isAvailable(name)) return;
  if (name == kMujoco) {
    throw std::invalid_argument(
        "engine 'mujoco' is not built: install Debian's libmujoco-dev (apt-get install "
        "libmujoco-dev; scripts/bootstrap.sh does) and configure the build again, which then "
        "builds the optional MuJoCo engine");
  }
  std::string known;
  for (const std::string& e : knownEngines()) known += (known.empty() ? "" : ", ") + e;
  throw std::invalid_argument("unknown engine '" + std::string(name) + "' (expected one of " +
                              known + ")");
}

std::shared_ptr<const trial::EngineFactory> engineFactory(std::string_view name,
                                                          const dynamics::DynamicWorkCell& dwc,
                                                          const trial::GraspTrialSetup& setup) {
  checkEngine(name);
  if (name == kDefaultEngine) return nullptr;
#ifdef VISGRAB_WITH_MUJOCO
  (void)setup;
  return mujoco::mujocoEngineFactory(dwc);
#else
  (void)dwc;
  (void)setup;
  return nullptr;
#endif
}

}  // namespace rwsim::engines
