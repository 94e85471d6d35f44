// The benchmark's stage times with injected clocks: each stage's wall and CPU time is the
// difference of the clocks at its start and stop, the total their sum, as a table and as CSV.
#include "stage_times.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace {

using visgrab::app::StageTimes;

TEST(StageTimes, MeasuresEachStageBetweenStartAndStop) {
  double wall = 100.0;
  double cpu = 7.0;
  StageTimes times([&] { return wall; }, [&] { return cpu; });
  times.start("database");
  wall += 81.26;
  cpu += 160.54;
  times.stop("432 scenes generated");
  wall += 5.0;  // between stages: counted in none
  cpu += 1.0;
  times.start("report");
  wall += 0.52;
  cpu += 0.27;
  times.stop();
  ASSERT_EQ(times.stages().size(), 2u);
  EXPECT_EQ(times.stages()[0].name, "database");
  EXPECT_NEAR(times.stages()[0].wall, 81.26, 1e-9);
  EXPECT_NEAR(times.stages()[0].cpu, 160.54, 1e-9);
  EXPECT_EQ(times.stages()[0].note, "432 scenes generated");
  EXPECT_NEAR(times.stages()[1].wall, 0.52, 1e-9);
  EXPECT_NEAR(times.stages()[1].cpu, 0.27, 1e-9);

  EXPECT_EQ(times.table(),
            "stage times (wall, process CPU):\n"
            "  database       81.3 s     160.5 s  432 scenes generated\n"
            "  report          0.5 s       0.3 s\n"
            "  total          81.8 s     160.8 s\n");
  EXPECT_EQ(times.csv(),
            "stage,wall_s,cpu_s,note\n"
            "database,81.260,160.540,432 scenes generated\n"
            "report,0.520,0.270,\n"
            "total,81.780,160.810,\n");
}

TEST(StageTimes, QuotesNotesWithCommas) {
  double now = 0.0;
  StageTimes times([&] { return now; }, [&] { return now; });
  times.start("trials");
  now = 2.0;
  times.stop("10 trials run, 3 resumed, \"x\"");
  EXPECT_NE(times.csv().find("trials,2.000,2.000,\"10 trials run, 3 resumed, \"\"x\"\"\"\n"),
            std::string::npos)
      << times.csv();
}

TEST(StageTimes, StartAndStopMustAlternate) {
  StageTimes times([] { return 0.0; }, [] { return 0.0; });
  EXPECT_THROW(times.stop(), std::logic_error);
  times.start("a");
  EXPECT_THROW(times.start("b"), std::logic_error);
  times.stop();
  EXPECT_THROW(times.stop(), std::logic_error);
}

TEST(StageTimes, DefaultClocksCountCpuTimeOfTheProcess) {
  StageTimes times;
  times.start("spin");
  volatile double x = 0.0;
  // Busy work until the process CPU clock has moved: its time must show in the stage.
  for (int i = 0; i < 50'000'000; ++i) x = x + 1e-9 * i;
  times.stop();
  EXPECT_GT(times.stages()[0].cpu, 0.0);
  EXPECT_GT(times.stages()[0].wall, 0.0);
}

}  // namespace
