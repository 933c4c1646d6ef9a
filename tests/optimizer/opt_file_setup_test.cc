// mrsim-opt FILE: the design's <optimization> fills what the command line
// leaves out, a flag overrides the file, and a bad value names the file's
// line and field.
#include "optimizer/process/opt_file_setup.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "optimizer/search/algorithm_registry.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

// Parses `args` as mrsim-opt does and applies the file's setup.
OptCommand ParseWithFile(std::vector<std::string> args) {
  CLI::App app;
  OptCommand command;
  AddOptFlags(app, command);
  std::reverse(args.begin(), args.end());  // CLI11 takes them reversed
  app.parse(args);
  ApplyFileSetup(app, &command);
  return command;
}

// snake11 with `setup` saved in it, in a folder of its own.
std::string DesignWith(const std::string& name,
                       const OptimizationSettings& setup) {
  Scenario s = ReadScenarioFile(testing::SourcePath("scenarios/snake11.xml"));
  s.optimization = setup;
  const std::string path = testing::TempDir(name) + "/design.xml";
  WriteScenarioFile(s, path);
  return path;
}

OptimizationSettings SmallCmaes() {
  OptimizationSettings o;
  o.algorithm = "cmaes";
  o.generations = 5;
  o.population = 3;
  o.seed = 7;
  o.episode = 0.5;
  o.genes = "cpg";
  o.w_energy = 0.25;
  o.robust_mode = "worst";
  o.algorithm_settings = "cmaes-sigma=0.2";
  return o;
}

// A field left out of a file means what leaving out its flag means.
TEST(OptFileSetup, TheFilesDefaultsAreMrsimOptsDefaults) {
  const OptCommand defaults;
  OptCommand applied;
  ApplyOptimizationSettings(
      OptimizationSettings{}, [](const std::string&) { return false; }, "f", "",
      [](const std::string&) { return 0; }, &applied);
  EXPECT_EQ(applied.algorithm.algorithm, defaults.algorithm.algorithm);
  EXPECT_EQ(applied.generations, defaults.generations);
  EXPECT_EQ(applied.algorithm.population, defaults.algorithm.population);
  EXPECT_EQ(applied.algorithm.seed, defaults.algorithm.seed);
  EXPECT_EQ(applied.episode.duration, defaults.episode.duration);
  EXPECT_EQ(applied.controller, defaults.controller);
  EXPECT_EQ(applied.genes, defaults.genes);
  EXPECT_EQ(applied.gait_spec, defaults.gait_spec);
  const FitnessSettings& f = applied.episode.fitness;
  const FitnessSettings& d = defaults.episode.fitness;
  EXPECT_EQ(f.distance_mode, d.distance_mode);
  EXPECT_EQ(f.w_distance, d.w_distance);
  EXPECT_EQ(f.w_speed, d.w_speed);
  EXPECT_EQ(f.w_energy, d.w_energy);
  EXPECT_EQ(f.w_drift, d.w_drift);
  EXPECT_EQ(f.w_fall, d.w_fall);
  EXPECT_EQ(applied.episode.robust.episodes, defaults.episode.robust.episodes);
  EXPECT_EQ(applied.episode.robust.mode, defaults.episode.robust.mode);
  EXPECT_EQ(applied.allow_overlap, defaults.allow_overlap);
  const RealityGap& g = applied.episode.robust.gap;
  const RealityGap typical = RealityGap::Typical();
  EXPECT_EQ(g.sensor_noise, typical.sensor_noise);
  EXPECT_EQ(g.sensor_bias, typical.sensor_bias);
  EXPECT_EQ(g.joint_noise, typical.joint_noise);
  EXPECT_EQ(g.motor_noise, typical.motor_noise);
  EXPECT_EQ(g.latency, typical.latency);
  EXPECT_EQ(g.backlash, typical.backlash);
  EXPECT_EQ(g.max_accel, typical.max_accel);
  EXPECT_EQ(g.friction_range, typical.friction_range);
  EXPECT_EQ(g.mass_range, typical.mass_range);
  EXPECT_EQ(g.gain_range, typical.gain_range);
  EXPECT_EQ(g.terrain_range, typical.terrain_range);
}

// The design's reality gap is what the robust episodes perturb by.
TEST(OptFileSetup, TheFilesRealityGapReachesTheRobustEpisodes) {
  OptimizationSettings o = SmallCmaes();
  o.robust = 3;
  o.gap_motor_noise = 0.7;
  o.gap_latency = 0;
  o.gap_friction_range = 0.6;
  const OptCommand c = ParseWithFile({DesignWith("opt_file_gap", o)});
  const RobustSettings& r = c.episode.robust;
  EXPECT_EQ(r.episodes, 3);
  EXPECT_EQ(r.gap.motor_noise, 0.7);
  EXPECT_EQ(r.gap.latency, 0);
  EXPECT_EQ(r.gap.friction_range, 0.6);
  EXPECT_EQ(r.gap.mass_range, RealityGap::Typical().mass_range);
  EXPECT_NO_THROW(r.Validate());
}

// --robust-gap NAME=VALUE sets one value over the file's; the rest stay.
TEST(OptFileSetup, ARobustGapFlagOverridesTheFilesValue) {
  OptimizationSettings o = SmallCmaes();
  o.gap_motor_noise = 0.7;
  o.gap_backlash = 0.1;
  const OptCommand c =
      ParseWithFile({DesignWith("opt_file_gap_flag", o), "--robust-gap",
                     "motor_noise=0.2", "--robust-gap", "max_accel=0"});
  RealityGap gap = c.episode.robust.gap;
  SetGapValues(c.robust_gap, &gap);
  EXPECT_EQ(gap.motor_noise, 0.2);
  EXPECT_EQ(gap.max_accel, 0);
  EXPECT_EQ(gap.backlash, 0.1);  // the file's
  EXPECT_THROW(SetGapValues({"latency=2"}, &gap), OptInputError);
  try {
    SetGapValues({"noise=0.1"}, &gap);
    ADD_FAILURE() << "accepted an unknown name";
  } catch (const OptInputError& e) {
    EXPECT_NE(std::string(e.what()).find("motor_noise"), std::string::npos)
        << e.what();
  }
}

TEST(OptFileSetup, TheFileFillsWhatTheCommandLineLeavesOut) {
  const std::string design = DesignWith("opt_file_fill", SmallCmaes());
  const OptCommand c = ParseWithFile({design});
  EXPECT_EQ(c.algorithm.algorithm, AlgorithmKind::kCmaes);
  EXPECT_EQ(c.generations, 5);
  EXPECT_EQ(c.algorithm.population, 3);
  EXPECT_EQ(c.algorithm.seed, 7u);
  EXPECT_EQ(c.episode.duration, 0.5);
  EXPECT_EQ(c.genes, "cpg");
  EXPECT_EQ(c.episode.fitness.w_energy, 0.25);
  EXPECT_EQ(c.episode.robust.mode, "worst");
  EXPECT_EQ(c.algorithm.cmaes_sigma, 0.2);
  EXPECT_EQ(c.out_dir, "opt-design");  // no --out: beside, named after it
}

TEST(OptFileSetup, AFlagOnTheCommandLineOverridesTheFile) {
  const std::string design = DesignWith("opt_file_override", SmallCmaes());
  const OptCommand c =
      ParseWithFile({design, "--seed", "9", "--genes", "sine", "--cmaes-sigma",
                     "0.3", "--out", "elsewhere"});
  EXPECT_EQ(c.algorithm.seed, 9u);
  EXPECT_EQ(c.genes, "sine");
  EXPECT_EQ(c.algorithm.cmaes_sigma, 0.3);
  EXPECT_EQ(c.out_dir, "elsewhere");
  EXPECT_EQ(c.algorithm.algorithm, AlgorithmKind::kCmaes);  // the file's
}

TEST(OptFileSetup, AValueMrsimOptRefusesNamesTheFilesLineAndField) {
  struct Bad {
    void (*set)(OptimizationSettings*);
    std::string field;
    std::string expected;
  };
  for (const Bad& bad : std::vector<Bad>{
           {[](OptimizationSettings* o) { o->algorithm = "hill"; }, "algorithm",
            "hill"},
           {[](OptimizationSettings* o) { o->distance = "sideways"; },
            "distance", "sideways"},
           {[](OptimizationSettings* o) { o->genes = "legs"; }, "genes",
            "legs"},
           {[](OptimizationSettings* o) { o->task = "moon"; }, "task", "moon"},
           {[](OptimizationSettings* o) { o->robust_mode = "best"; },
            "robustMode", "mean or worst"},
           {[](OptimizationSettings* o) { o->algorithm_settings = "x=1"; },
            "algorithmSettings", "'x=1'"},
           {[](OptimizationSettings* o) { o->genome = "<genome"; }, "genome",
            "genome"}}) {
    OptimizationSettings o;
    bad.set(&o);
    const std::string design = DesignWith("opt_file_bad", o);
    try {
      ParseWithFile({design});
      ADD_FAILURE() << "accepted a bad " << bad.field;
    } catch (const OptInputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(design + ":"), std::string::npos) << what;
      EXPECT_NE(what.find("Scenario/optimization/" + bad.field),
                std::string::npos)
          << what;
      EXPECT_NE(what.find(bad.expected), std::string::npos) << what;
      // A line number after the file name.
      const std::string after = what.substr(design.size() + 1);
      EXPECT_TRUE(!after.empty() && std::isdigit(after[0])) << what;
    }
  }
}

// The run the file describes is the run of the same flags: same seed, same
// genes, same algorithm, same best.
TEST(OptFileSetup, MrsimOptFileRunsAsTheEquivalentFlags) {
  OptimizationSettings setup = SmallCmaes();
  setup.genes = "sine";
  const std::string design = DesignWith("opt_file_run", setup);
  const auto run = [](const OptCommand& c) {
    const OptSetup prepared = PrepareOpt(c);
    auto evaluator = MakeOptEvaluator(c, prepared, nullptr, nullptr);
    std::FILE* sink = std::tmpfile();
    const OptOutcome outcome = RunOpt(c, prepared, *evaluator, sink, sink);
    std::fclose(sink);
    return outcome;
  };
  const std::string dir = testing::TempDir("opt_file_run_out");
  const OptOutcome from_file =
      run(ParseWithFile({design, "--generations", "2", "--workers", "local:1",
                         "--out", dir + "/file"}));
  const OptOutcome from_flags =
      run(ParseWithFile({testing::SourcePath("scenarios/snake11.xml"),
                         "--algorithm",
                         "cmaes",
                         "--generations",
                         "2",
                         "--population",
                         "3",
                         "--seed",
                         "7",
                         "--episode",
                         "0.5",
                         "--genes",
                         "sine",
                         "--w-energy",
                         "0.25",
                         "--robust-mode",
                         "worst",
                         "--cmaes-sigma",
                         "0.2",
                         "--workers",
                         "local:1",
                         "--out",
                         dir + "/flags"}));
  EXPECT_EQ(from_file.result.generations_done, 2);
  EXPECT_EQ(from_file.result.best, from_flags.result.best);
  EXPECT_EQ(from_file.result.best_result.fitness,
            from_flags.result.best_result.fitness);
  EXPECT_EQ(from_file.result.evaluations, 6);
}

}  // namespace
}  // namespace mrsim
