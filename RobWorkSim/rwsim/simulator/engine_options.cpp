#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "rwsim/simulator/simulator.hpp"

namespace rwsim::simulator {

namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

double parseNumber(const std::string& key, const std::string& text, bool allowZero) {
  const std::string t = trimmed(text);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v) || v < 0.0 ||
      (!allowZero && v == 0.0)) {
    throw std::invalid_argument("PhysicsEngine property " + key + ": '" + text + "' is not a " +
                                (allowZero ? "non-negative" : "positive") + " number");
  }
  return v;
}

std::string parseStepMethod(const std::string& text) {
  const std::string t = trimmed(text);
  if (t == "WorldStep" || t == "WorldFast1") return "WorldStep";  // RobWork: Fast1 -> WorldStep
  if (t == "WorldQuickStep") return "WorldQuickStep";
  throw std::invalid_argument("PhysicsEngine property StepMethod: '" + text +
                              "' is not WorldStep, WorldQuickStep or WorldFast1");
}

}  // namespace

SimulatorOptions optionsFromEngineProperties(const dynamics::DynamicWorkCell& dwc,
                                             SimulatorOptions defaults) {
  SimulatorOptions o = std::move(defaults);
  for (const auto& [key, value] : dwc.engineProperties()) {
    if (key == "StepMethod") {
      o.stepMethod = parseStepMethod(value);
    } else if (key == "WorldCFM") {
      o.worldCfm = parseNumber(key, value, true);
    } else if (key == "WorldERP") {
      o.worldErp = parseNumber(key, value, true);
      if (o.worldErp > 1.0) {
        throw std::invalid_argument("PhysicsEngine property WorldERP: '" + value + "' is above 1");
      }
    } else if (key == "ContactSurfaceLayer") {
      o.contactSurfaceLayer = parseNumber(key, value, true);
    } else if (key == "MaxSepDistance") {
      o.contacts.margin = parseNumber(key, value, true);
    } else if (key == "MaxCorrectingVelocity") {
      o.maxCorrectingVelocity = parseNumber(key, value, false);
    }
    // Other RobWork keys (MaxIterations, SpaceType, MaxPenetration, ContactClusteringAlg, ...)
    // have no effect here, as most of them had none in RobWork either (reference §8.3).
  }
  return o;
}

}  // namespace rwsim::simulator
