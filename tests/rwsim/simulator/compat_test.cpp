// RobWork's own dynamic workcells load and simulate (needs RW_COMPAT_DATA).
#include <gtest/gtest.h>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "support/test_support.hpp"

namespace {

using rwsim::simulator::Simulator;
using rwsim::simulator::StepStatus;

// Simulates `seconds` with the file's engine settings; returns the simulator's end time.
double simulate(const std::filesystem::path& file, double seconds) {
  auto dwc = rwsim::loaders::loadDynamicWorkCell(file);
  Simulator sim(*dwc, rwsim::simulator::optionsFromEngineProperties(*dwc));
  while (sim.time() < seconds - 1e-9) {
    const StepStatus s = sim.step();
    EXPECT_EQ(s, StepStatus::kOk) << file << " at t = " << sim.time() << ": "
                                  << sim.failureDetail();
    if (s != StepStatus::kOk) break;
  }
  return sim.time();
}

TEST(SimulatorCompat, RobWorkSdhTestSceneSimulatesTwoSeconds) {
  REQUIRE_COMPAT_DATA(data);
  EXPECT_NEAR(simulate(data / "devices/SDH2/test_scene.dwc.xml", 2.0), 2.0, 1e-9);
}

TEST(SimulatorCompat, RobWorkPg70BoxSceneSimulatesTwoSeconds) {
  REQUIRE_COMPAT_DATA(data);
  auto dwc = rwsim::loaders::loadDynamicWorkCell(data / "scene/grasping/pg70_box.dwc.xml");
  Simulator sim(*dwc, rwsim::simulator::optionsFromEngineProperties(*dwc));
  const auto object = dwc->findBody("object");
  ASSERT_TRUE(object.valid());
  while (sim.time() < 2.0 - 1e-9) {
    ASSERT_EQ(sim.step(), StepStatus::kOk) << "t = " << sim.time() << ": " << sim.failureDetail();
  }
  // The box starts 1 cm above the floor (reference §6.3): it drops and comes to rest on it.
  EXPECT_NEAR(sim.bodyPose(object).translation().z(), 0.05, 2e-3);
  EXPECT_LT(sim.bodyLinearVelocity(object).norm(), 1e-2);
}

}  // namespace
