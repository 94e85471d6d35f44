// compareWithLabels (`visgrab agreement RUN --labels FILE`) on a hand-made run and labels,
// every figure worked by hand below.
#include "visgrab/analysis/label_agreement.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

using visgrab::analysis::AgreementRun;
using visgrab::analysis::compareWithLabels;
using visgrab::analysis::LabelAgreement;
using Outcome = rwsim::trial::GraspOutcome;

const std::string kScene = "plain/single/table/01";

visgrab::results::TrialRecord trial(const std::string& scene, const std::string& method,
                                    const std::string& grasp, Outcome outcome, int repeat = 0) {
  visgrab::results::TrialRecord t;
  t.sceneId = scene;
  t.method = method;
  t.graspId = grasp;
  t.outcome = outcome;
  t.repeat = repeat;
  return t;
}

// Labels of grasps 0..7: 1 1 1 0 0 1 0 1. The run's trials of method "acro" in kScene:
//   grasp  outcome        held  label
//   0      stable         H     1      both held
//   1      slipped        H     1      both held
//   2      dropped        -     1      only the labels
//   3      stable         H     0      only the run
//   4      missed         -     0      neither
//   5      in_collision   -     1      only the labels (decided before simulation: not held)
//   6      missed         -     0      neither
//   7      (no trial)                  without a trial
// Ignored: grasp 9 (no such label) and "x" (not an index): unmatched; grasp 0's repeat 1; a
// trial of another scene.
// Every compared grasp (n 7): a 2, b 1, c 2, d 2:
//   p_o = 4/7, p_run = 3/7, p_labels = 4/7, p_e = 3/7 * 4/7 + 4/7 * 3/7 = 24/49,
//   kappa = (28/49 - 24/49) / (25/49) = 4/25 = 0.16.
// The simulated ones (n 6, without grasp 5): a 2, b 1, c 1, d 2:
//   p_o = 2/3, p_run = p_labels = 1/2, p_e = 1/2, kappa = (2/3 - 1/2) / (1/2) = 1/3.
AgreementRun run(bool withOtherMethod) {
  AgreementRun r;
  r.dir = "/runs/acro";
  auto& trials = r.results.trials;
  trials.push_back(trial(kScene, "acro", "0", Outcome::kStable));
  trials.push_back(trial(kScene, "acro", "0", Outcome::kDropped, 1));
  trials.push_back(trial(kScene, "acro", "1", Outcome::kSlipped));
  trials.push_back(trial(kScene, "acro", "2", Outcome::kDropped));
  trials.push_back(trial(kScene, "acro", "3", Outcome::kStable));
  trials.push_back(trial(kScene, "acro", "4", Outcome::kMissed));
  trials.push_back(trial(kScene, "acro", "5", Outcome::kInCollision));
  trials.push_back(trial(kScene, "acro", "6", Outcome::kMissed));
  trials.push_back(trial(kScene, "acro", "9", Outcome::kStable));
  trials.push_back(trial(kScene, "acro", "x", Outcome::kStable));
  trials.push_back(trial("plain/single/chair/01", "acro", "2", Outcome::kStable));
  if (withOtherMethod) {
    // Another method's grasps with the same ids: all dropped. Were they compared, the figures
    // above would change.
    for (const char* id : {"0", "1", "3"}) {
      trials.push_back(trial(kScene, "other", id, Outcome::kDropped));
    }
  }
  return r;
}

const std::vector<int> kLabels = {1, 1, 1, 0, 0, 1, 0, 1};

void expectHandWorkedFigures(const LabelAgreement& g) {
  EXPECT_EQ(g.method, "acro");
  EXPECT_EQ(g.labels, 8);
  EXPECT_EQ(g.missingTrials, 1);
  EXPECT_EQ(g.unmatchedTrials, 2);
  EXPECT_EQ(g.decidedBeforeSimulation, 1);
  EXPECT_EQ(g.held.trials, 7);
  EXPECT_EQ(g.held.bothHeld, 2);
  EXPECT_EQ(g.held.onlyAHeld, 1);
  EXPECT_EQ(g.held.onlyBHeld, 2);
  EXPECT_EQ(g.held.neitherHeld, 2);
  EXPECT_EQ(g.held.sameOutcome, 4);
  EXPECT_NEAR(g.held.observedAgreement, 4.0 / 7.0, 1e-12);
  EXPECT_NEAR(g.held.expectedAgreement, 24.0 / 49.0, 1e-12);
  EXPECT_NEAR(g.held.kappa, 0.16, 1e-12);
  EXPECT_EQ(g.simulated.trials, 6);
  EXPECT_EQ(g.simulated.onlyBHeld, 1);
  EXPECT_EQ(g.simulated.sameOutcome, 4);
  EXPECT_NEAR(g.simulated.kappa, 1.0 / 3.0, 1e-12);
  // Outcome by label (not held, held).
  const auto row = [&](Outcome o) { return g.confusion[static_cast<std::size_t>(o)]; };
  EXPECT_EQ(row(Outcome::kStable)[0], 1);
  EXPECT_EQ(row(Outcome::kStable)[1], 1);
  EXPECT_EQ(row(Outcome::kSlipped)[1], 1);
  EXPECT_EQ(row(Outcome::kDropped)[1], 1);
  EXPECT_EQ(row(Outcome::kMissed)[0], 2);
  EXPECT_EQ(row(Outcome::kInCollision)[1], 1);
  ASSERT_EQ(g.disagreements.size(), 3u);
  EXPECT_EQ(g.disagreements[0].graspId, "2");
  EXPECT_EQ(g.disagreements[1].graspId, "3");
  EXPECT_FALSE(g.disagreements[1].label);
  EXPECT_EQ(g.disagreements[2].outcome, Outcome::kInCollision);
}

TEST(LabelAgreement, TheOnlyMethodsTrialsAgainstTheLabelsWorkedByHand) {
  const LabelAgreement g = compareWithLabels(run(false), kLabels, "table.h5", kScene);
  expectHandWorkedFigures(g);
  // The disagreements name their trial and how to draw it.
  const std::string csv = visgrab::analysis::labelDisagreementsCsv(g);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "scene,method,grasp_id,outcome,label,render");
  EXPECT_NE(
      csv.find("\n" + kScene + ",acro,2,dropped,1,visgrab render --results /runs/acro --scene " +
               kScene + " --method acro --grasp 2 --out label-2.png\n"),
      std::string::npos)
      << csv;
  // A lift run gets a note (the labels are a shake's); a shake run none.
  EXPECT_NE(visgrab::analysis::labelProtocolNote(g).find("ran the lift protocol"),
            std::string::npos);
  AgreementRun shaken = run(false);
  shaken.results.sources.protocol = "shake";
  EXPECT_EQ(
      visgrab::analysis::labelProtocolNote(compareWithLabels(shaken, kLabels, "table.h5", kScene)),
      "");
}

TEST(LabelAgreement, SeveralMethodsInTheSceneNeedTheOneNamed) {
  const AgreementRun both = run(true);
  try {
    compareWithLabels(both, kLabels, "table.h5", kScene);
    ADD_FAILURE() << "two methods were compared as one";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "/runs/acro ran 2 methods in scene " + kScene +
                                         " (acro, other): name the one whose grasps are those "
                                         "of table.h5 with --method");
  }
  // Named, only its trials count: the same figures as without the other method.
  expectHandWorkedFigures(compareWithLabels(both, kLabels, "table.h5", kScene, "acro"));
  try {
    compareWithLabels(both, kLabels, "table.h5", kScene, "mine");
    ADD_FAILURE() << "an absent method was compared";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "/runs/acro has no trial of method mine in scene " + kScene +
                                         " (its methods there: acro, other)");
  }
  try {
    compareWithLabels(both, kLabels, "table.h5", "plain/single/sofa/01");
    ADD_FAILURE() << "a scene without trials was compared";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has no trial of scene plain/single/sofa/01"),
              std::string::npos)
        << e.what();
  }
}

TEST(LabelAgreement, ALabelThatIsNotZeroOrOneIsAnError) {
  try {
    compareWithLabels(run(false), {1, 2}, "table.h5", kScene);
    ADD_FAILURE() << "label 2 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "table.h5: label 1 is 2, expected 0 or 1");
  }
}

}  // namespace
