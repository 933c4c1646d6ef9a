// The studio's optimisation settings reach mrsim-opt's command line: the
// fitness, the base gait and the chosen algorithm's own settings from the
// algorithm registry; why individuals failed reaches the panel from
// mrsim-opt's progress line.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimizer/process/opt_command.h"
#include "optimizer/search/algorithm.h"
#include "optimizer/search/algorithm_registry.h"
#include "studio/live/optimise_session.h"

namespace mrsim::studio {
namespace {

OptimiseOptions Options() {
  OptimiseOptions o;
  o.scenario_path = "robot.xml";
  o.out_dir = "opt";
  return o;
}

// The value after `flag`, "" when the flag is missing.
std::string After(const std::vector<std::string>& args,
                  const std::string& flag) {
  auto it = std::find(args.begin(), args.end(), flag);
  return it == args.end() || it + 1 == args.end() ? "" : *(it + 1);
}

TEST(OptimiseSpec, FitnessWeightsDistanceModeAndBaseGaitReachMrsimOpt) {
  OptimiseOptions o = Options();
  o.fitness.distance_mode = DistanceMode::kNet;
  o.fitness.w_energy = 0.25;
  o.fitness.w_fall = 3;
  o.base_gait = "turn_left";
  const ProcessSpec spec = OptimiseSession::Spec(o, "g.xml");
  EXPECT_EQ(After(spec.args, "--distance"), "net");
  EXPECT_EQ(After(spec.args, "--w-distance"), "1");
  EXPECT_EQ(After(spec.args, "--w-energy"), "0.25");
  EXPECT_EQ(After(spec.args, "--w-fall"), "3");
  EXPECT_EQ(After(spec.args, "--gait"), "turn_left");
}

TEST(OptimiseSpec, RobustFitnessReachesMrsimOptOnlyWhenAsked) {
  OptimiseOptions o = Options();
  EXPECT_EQ(After(OptimiseSession::Spec(o, "g.xml").args, "--robust"), "")
      << "the nominal world: mrsim-opt's default";
  o.robust.episodes = 4;
  o.robust.mode = "worst";
  const ProcessSpec spec = OptimiseSession::Spec(o, "g.xml");
  EXPECT_EQ(After(spec.args, "--robust"), "4");
  EXPECT_EQ(After(spec.args, "--robust-mode"), "worst");
  o.robust.mode = "median";
  EXPECT_THROW(OptimiseSession::Spec(o, "g.xml"), std::invalid_argument);
}

TEST(OptimiseSpec, AllowingOverlapInRunAllowsItInTheOptimiserToo) {
  OptimiseOptions o = Options();
  auto has = [](const std::vector<std::string>& args) {
    return std::find(args.begin(), args.end(), "--allow-overlap") != args.end();
  };
  EXPECT_FALSE(has(OptimiseSession::Spec(o, "g.xml").args));
  o.allow_overlap = true;
  EXPECT_TRUE(has(OptimiseSession::Spec(o, "g.xml").args));
}

TEST(OptimiseSpec, TheChosenAlgorithmsOwnSettingsArePassed) {
  OptimiseOptions o = Options();
  o.algorithm = "pso";
  o.algorithm_settings = {{"pso-c1", 2.0}, {"pso-inertia", 0.7298}};
  const ProcessSpec spec = OptimiseSession::Spec(o, "g.xml");
  EXPECT_EQ(After(spec.args, "--pso-c1"), "2");
  EXPECT_EQ(After(spec.args, "--pso-inertia"), "0.7298");
}

TEST(OptimiseSpec, AnotherAlgorithmsSettingIsRefusedByName) {
  OptimiseOptions o = Options();
  o.algorithm = "cmaes";
  o.algorithm_settings = {{"pso-c1", 2.0}};
  try {
    OptimiseSession::Spec(o, "g.xml");
    FAIL() << "accepted a PSO setting for CMA-ES";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pso-c1"), std::string::npos)
        << e.what();
  }
}

TEST(AlgorithmRegistrySettings, EveryRowsSettingsReadAndWriteTheirField) {
  for (const AlgorithmInfo& info : Algorithms()) {
    for (const AlgorithmSetting& s : info.settings) {
      SCOPED_TRACE(s.flag);
      EXPECT_EQ(FindAlgorithmSetting(s.flag), &s);
      EXPECT_TRUE((s.real == nullptr) != (s.whole == nullptr));
      EXPECT_LE(s.min, s.max);
      AlgorithmSettings settings;
      const double value = s.real ? (s.min + s.max) / 2 : s.min + 1;
      s.Set(&settings, value);
      EXPECT_DOUBLE_EQ(s.Get(settings), value);
    }
  }
  EXPECT_EQ(FindAlgorithmSetting("no-such-setting"), nullptr);
  EXPECT_FALSE(AlgorithmInfoOf(AlgorithmKind::kPso).settings.empty());
}

// The Optimise panel shows why individuals failed, from mrsim-opt's own
// progress line (FormatProgress, the line a run prints).
TEST(OptimiseSpec, TheReasonIndividualsFailedIsTakenFromTheProgressLine) {
  GenerationReport r;
  r.generation = 3;
  r.generations = 10;
  r.best = 0.2;
  r.mean = -1e6;
  r.best_so_far = 0.25;
  r.evals_per_second = 4.5;
  r.workers = 1;
  r.eta_seconds = 12;
  EXPECT_EQ(OptimiseSession::FailedNote(FormatProgress(r)), "");
  r.failed = 2;
  r.failed_reasons = {
      {"robot 'snake' module 3 front frame overlaps scene object 'ball' by "
       "12.0 mm at the start",
       2}};
  EXPECT_EQ(OptimiseSession::FailedNote(FormatProgress(r)),
            "generation 3: failed 2 (robot 'snake' module 3 front frame "
            "overlaps scene object 'ball' by 12.0 mm at the start)");
  r.island = 1;
  EXPECT_EQ(OptimiseSession::FailedNote(FormatProgress(r))
                .rfind("generation 3: failed 2 (robot", 0),
            0u);
  EXPECT_EQ(OptimiseSession::FailedNote("opt exited with code 2"), "");
}

}  // namespace
}  // namespace mrsim::studio
