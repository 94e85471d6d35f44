// Every scene of the shared test database (tests/support/test_database.hpp: the project's
// objects, both tables, the SDH) exports to MJCF, compiles in MuJoCo, puts every body where the
// scene's state does, and settles without a failing step.
#include <gtest/gtest.h>

#include <string>

#include "rw/kinematics/frame_tree.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/mujoco/mujoco_engine.hpp"
#include "support/test_database.hpp"
#include "support/test_support.hpp"

namespace {

TEST(MujocoDatabase, EveryTestSceneExportsCompilesAndStartsWhereTheSceneSays) {
  const auto& database = visgrab::test::testDatabase();
  ASSERT_EQ(database.list().size(), visgrab::test::kTestSceneIds.size());
  for (const auto& entry : database.list()) {
    SCOPED_TRACE(entry.id);
    const auto dwc = rwsim::loaders::loadDynamicWorkCell(entry.dynamicWorkcell);
    std::shared_ptr<const rwsim::trial::EngineFactory> factory;
    ASSERT_NO_THROW(factory = rwsim::mujoco::mujocoEngineFactory(*dwc));
    const auto engine = factory->create();
    const auto state = dwc->workcell().defaultState();
    engine->reset(state);
    const rw::kinematics::FKTable fk(dwc->workcell().frames(), state);
    for (std::size_t b = 0; b < dwc->bodies().size(); ++b) {
      const auto& body = dwc->bodies()[b];
      EXPECT_TRANSFORM_NEAR(engine->bodyPose(rwsim::dynamics::BodyId(b)),
                            fk.worldTransform(body.frame), 1e-9)
          << body.name;
    }
    for (int step = 0; step < 100; ++step) {
      ASSERT_EQ(engine->step(), rwsim::trial::StepStatus::kOk) << engine->failureDetail();
    }
  }
}

}  // namespace
