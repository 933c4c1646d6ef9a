// How to optimise a design travels with it: what the Optimise form saves is
// what opening the file gives back, and Start optimisation then asks
// mrsim-opt for the run the file describes.
#include "studio/live/saved_optimisation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "optimizer/search/genome.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/design.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

OptimiseOptions CmaesForm() {
  OptimiseOptions o;
  o.algorithm = "cmaes";
  o.generations = 7;
  o.population = 5;
  o.seed = 11;
  o.episode_s = 2.5;
  o.genome = BuiltInGenome("cpg");
  o.genome.genes[0].enabled = false;  // an edited gene set
  o.genome.genes[1].upper = 1.2;
  o.base_gait = "turn_left";
  o.fitness.distance_mode = DistanceMode::kNet;
  o.fitness.w_energy = 0.05;
  o.fitness.w_fall = 2;
  o.robust.episodes = 3;
  o.robust.mode = "worst";
  o.robust.gap.motor_noise = 0.4;  // a servo noisier than typical
  o.robust.gap.latency = 0.05;
  o.robust.gap.max_accel = 0;
  o.robust.gap.terrain_range = 0.5;
  o.allow_overlap = true;
  o.algorithm_settings["cmaes-sigma"] = 0.25;
  return o;
}

void ExpectSameForm(const OptimiseOptions& a, const OptimiseOptions& b) {
  EXPECT_EQ(a.algorithm, b.algorithm);
  EXPECT_EQ(a.generations, b.generations);
  EXPECT_EQ(a.population, b.population);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.episode_s, b.episode_s);
  EXPECT_EQ(a.controller, b.controller);
  EXPECT_EQ(WriteGenomeString(a.genome), WriteGenomeString(b.genome));
  EXPECT_EQ(a.task, b.task);
  EXPECT_EQ(a.base_gait, b.base_gait);
  EXPECT_EQ(a.fitness.distance_mode, b.fitness.distance_mode);
  EXPECT_EQ(a.fitness.w_energy, b.fitness.w_energy);
  EXPECT_EQ(a.fitness.w_fall, b.fitness.w_fall);
  EXPECT_EQ(a.robust.episodes, b.robust.episodes);
  EXPECT_EQ(a.robust.mode, b.robust.mode);
  const RealityGap &g = a.robust.gap, &h = b.robust.gap;
  EXPECT_EQ(g.sensor_noise, h.sensor_noise);
  EXPECT_EQ(g.sensor_bias, h.sensor_bias);
  EXPECT_EQ(g.joint_noise, h.joint_noise);
  EXPECT_EQ(g.motor_noise, h.motor_noise);
  EXPECT_EQ(g.latency, h.latency);
  EXPECT_EQ(g.backlash, h.backlash);
  EXPECT_EQ(g.max_accel, h.max_accel);
  EXPECT_EQ(g.friction_range, h.friction_range);
  EXPECT_EQ(g.mass_range, h.mass_range);
  EXPECT_EQ(g.gain_range, h.gain_range);
  EXPECT_EQ(g.terrain_range, h.terrain_range);
  EXPECT_EQ(a.allow_overlap, b.allow_overlap);
  EXPECT_EQ(a.algorithm_settings, b.algorithm_settings);
}

TEST(SavedOptimisation, OpeningTheSavedDesignGivesTheFormItWasSavedWith) {
  const std::string path =
      testing::TempDir("saved_optimisation") + "/design.xml";
  ChainScenarioOptions chain;
  chain.chain.modules = 2;
  Scenario s = MakeChainScenario(chain);
  s.optimization = SavedOptimisation(CmaesForm());
  WriteScenarioFile(s, path);
  const Design opened = Design::Open(path);
  ASSERT_TRUE(opened.scenario().optimization.has_value());
  // The changed reality gap is in the file; the rest stays typical.
  EXPECT_EQ(opened.scenario().optimization->gap_motor_noise, 0.4);
  EXPECT_EQ(opened.scenario().optimization->gap_mass_range,
            RealityGap::Typical().mass_range);
  const OptimiseOptions back =
      OptionsFromSaved(*opened.scenario().optimization, OptimiseOptions{});
  ExpectSameForm(back, CmaesForm());

  // Start optimisation asks mrsim-opt for that run.
  OptimiseOptions start = back;
  start.scenario_path = path;
  start.out_dir = "out";
  const ProcessSpec spec = OptimiseSession::Spec(start, "out/genome.xml");
  const auto has = [&](const std::string& flag, const std::string& value) {
    const auto at = std::find(spec.args.begin(), spec.args.end(), flag);
    return at != spec.args.end() && at + 1 != spec.args.end() &&
           *(at + 1) == value;
  };
  EXPECT_TRUE(has("--algorithm", "cmaes"));
  EXPECT_TRUE(has("--seed", "11"));
  EXPECT_TRUE(has("--generations", "7"));
  EXPECT_TRUE(has("--robust-mode", "worst"));
  EXPECT_TRUE(has("--cmaes-sigma", "0.25"));
  // The form's reality gap, every value (an unsaved edit runs too).
  EXPECT_EQ(std::count(spec.args.begin(), spec.args.end(), "--robust-gap"), 11);
  EXPECT_NE(std::find(spec.args.begin(), spec.args.end(), "motor_noise=0.4"),
            spec.args.end());
}

TEST(SavedOptimisation, ABuiltInGeneSetOpensAsItsGenes) {
  OptimizationSettings s;
  s.genes = "sine";
  EXPECT_EQ(WriteGenomeString(OptionsFromSaved(s, {}).genome),
            WriteGenomeString(BuiltInGenome("sine")));
  s.genes.clear();
  s.controller = "cpg";  // the gait, with the CPG's genes by default
  const OptimiseOptions cpg = OptionsFromSaved(s, {});
  EXPECT_EQ(cpg.controller, "gait");
  EXPECT_EQ(cpg.genome.size(), BuiltInGenome("cpg").size());
}

TEST(SavedOptimisation, AScriptsOrANetworksGenesAreNotSavedAsAGenome) {
  OptimiseOptions o = CmaesForm();
  o.controller = "lua";
  EXPECT_EQ(SavedOptimisation(o).genome, "");
  EXPECT_EQ(SavedOptimisation(o).controller, "lua");
  o.controller = "mlp:8";
  EXPECT_EQ(SavedOptimisation(o).controller, "mlp:8");
}

TEST(SavedOptimisation, AValueNoFormCanShowIsRefusedNamingTheField) {
  OptimizationSettings s;
  s.algorithm = "hill";
  try {
    OptionsFromSaved(s, {});
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("<algorithm>"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mrsim::studio
