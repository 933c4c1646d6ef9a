// Robust fitness (--robust K, docs/optimizer.md): the mean or worst over K
// perturbed worlds, the same worlds for every genome and on every worker.
#include <gtest/gtest.h>

#include "gait_controller/gait_presets.h"
#include "optimizer/episode/episode.h"
#include "optimizer/episode/problem_codec.h"
#include "sim_core/scenario/chain_builder.h"

namespace mrsim {
namespace {

Problem RobustProblem(int episodes, const std::string& mode) {
  Problem p;
  ChainScenarioOptions o;
  o.chain.modules = 6;
  o.friction = 0.6;
  p.scenario = MakeChainScenario(o);
  p.genome = ReadGenomeString(R"(<genome>
  <gene name="A_pitch" lower="0" upper="1.5" start="1"/>
  <gene name="phi_pitch" lower="0" upper="3.14" start="2.5"/>
  <gene name="T" lower="1" upper="6" start="2"/>
</genome>)",
                              "test genome");
  p.episode.duration = 1.0;
  p.episode.base_gait = *FindGaitPreset("forward");
  p.episode.robust.episodes = episodes;
  p.episode.robust.mode = mode;
  p.episode.robust.gap.seed = 11;
  return p;
}

TEST(RobustFitness, WorstIsNoBetterThanTheMeanAndTheSeedPicksTheWorlds) {
  const Problem mean = RobustProblem(4, "mean");
  const Genome g = mean.genome.StartGenome();
  const EvalResult m = RunEpisode(mean, g);
  const EvalResult w = RunEpisode(RobustProblem(4, "worst"), g);
  const EvalResult nominal = RunEpisode(RobustProblem(0, "mean"), g);
  EXPECT_FALSE(m.failed);
  EXPECT_LE(w.fitness, m.fitness);
  EXPECT_NE(m.fitness, nominal.fitness);
  // Same seed: the same result; another seed: other worlds.
  EXPECT_EQ(RunEpisode(mean, g).fitness, m.fitness);
  Problem other = mean;
  other.episode.robust.gap.seed = 12;
  EXPECT_NE(RunEpisode(other, g).fitness, m.fitness);
}

TEST(RobustFitness, PayloadCarriesTheWorldsSoAWorkerScoresTheSame) {
  const Problem p = RobustProblem(3, "worst");
  const Problem decoded = DecodeProblem(EncodeProblem(p), "test");
  EXPECT_EQ(decoded.episode.robust.episodes, 3);
  EXPECT_EQ(decoded.episode.robust.mode, "worst");
  EXPECT_EQ(decoded.episode.robust.gap.seed, 11u);
  EXPECT_EQ(decoded.episode.robust.gap.latency, p.episode.robust.gap.latency);
  const Genome g = p.genome.StartGenome();
  EXPECT_EQ(RunEpisode(decoded, g).fitness, RunEpisode(p, g).fitness);
  // A nominal problem's payload has no robust lines (its hash is as it was).
  EXPECT_EQ(EncodeProblem(RobustProblem(0, "mean")).find("robust"),
            std::string::npos);
}

TEST(RobustFitness, BadSettingsAreRefusedNamingThem) {
  Problem p = RobustProblem(2, "median");
  EXPECT_THROW(p.episode.Validate(), std::invalid_argument);
  p.episode.robust.mode = "mean";
  p.episode.robust.gap.mass_range = 2;
  EXPECT_THROW(p.episode.Validate(), std::invalid_argument);
  std::string payload = EncodeProblem(RobustProblem(2, "mean"));
  const size_t at = payload.find("robust_seed=11");
  ASSERT_NE(at, std::string::npos);
  payload.replace(at, 14, "robust_seed=-1");
  EXPECT_THROW(DecodeProblem(payload, "test"), ProblemError);
}

}  // namespace
}  // namespace mrsim
