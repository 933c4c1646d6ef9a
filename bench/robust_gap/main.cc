// BENCH robust_gap: CMA-ES on snake11's forward gait twice, same seed and
// budget (population 8, 10 generations, 5 s episodes): once on the nominal
// world, once with robust fitness (mean over 8 perturbed worlds,
// RealityGap::Typical()). Each best gait is replayed in 50 other perturbed
// worlds (another seed); its kept share is the mean fitness there over its
// nominal fitness. The figure is the robust gait's share over the nominal
// gait's (target >= 1.5). Small budget: a few minutes on two cores.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "gait_controller/gait_presets.h"
#include "optimizer/episode.h"
#include "optimizer/genome.h"
#include "optimizer/local_evaluator.h"
#include "optimizer/optimization_run.h"
#include "optimizer/problem_codec.h"
#include "sim_core/scenario_xml.h"

namespace {

constexpr int kReplayWorlds = 50;
// The budget of docs/physics.md's "Is a fast gait real?" run, whose
// nominal best tumbles end over end.
constexpr uint64_t kTrainSeed = 2;
constexpr double kEpisode = 5.0;
constexpr int kGenerations = 10;
constexpr uint64_t kReplaySeed = 1234567;

mrsim::Problem SnakeProblem(int robust) {
  mrsim::Problem p;
  p.scenario = mrsim::ReadScenarioFile(std::string(MRSIM_SOURCE_DIR) +
                                       "/scenarios/snake11.xml");
  p.genome = mrsim::ReadGenomeFile(std::string(MRSIM_SOURCE_DIR) +
                                   "/scenarios/forward_gait.genome.xml");
  p.episode.duration = kEpisode;
  p.episode.base_gait = *mrsim::FindGaitPreset("forward");
  p.episode.robust.episodes = robust;
  p.episode.robust.gap.seed = kTrainSeed;
  return mrsim::DecodeProblem(mrsim::EncodeProblem(p), "bench");
}

mrsim::Genome Optimise(const mrsim::Problem& problem) {
  mrsim::AlgorithmSettings a;
  a.algorithm = mrsim::ParseAlgorithm("cmaes");
  a.population = 8;
  a.seed = kTrainSeed;
  mrsim::OptimizationRunOptions options;
  options.generations = kGenerations;
  mrsim::LocalEvaluator evaluator(
      [&](const mrsim::Genome& g) { return mrsim::RunEpisode(problem, g); }, 2);
  return mrsim::RunOptimization(problem.genome, a, evaluator, options).best;
}

// Nominal fitness and mean fitness over the replay worlds.
std::pair<double, double> Replay(const mrsim::Genome& genome) {
  mrsim::Problem nominal = SnakeProblem(0);
  const double f0 = mrsim::RunEpisode(nominal, genome).fitness;
  mrsim::Problem worlds = nominal;
  worlds.episode.robust.episodes = kReplayWorlds;
  worlds.episode.robust.mode = "mean";
  worlds.episode.robust.gap.seed = kReplaySeed;
  // A failed world counts as no headway, not as the failure sentinel.
  double sum = 0;
  for (int k = 0; k < kReplayWorlds; ++k) {
    mrsim::Problem one = worlds;
    one.episode.robust.episodes = 1;
    one.episode.robust.gap = worlds.episode.robust.gap.ForEpisode(k);
    const mrsim::EvalResult r = mrsim::RunEpisode(one, genome);
    sum += r.failed ? 0.0 : r.fitness;
  }
  return {f0, sum / kReplayWorlds};
}

}  // namespace

int main() {
  double share[2] = {0, 0};
  for (int robust : {0, 8}) {
    const mrsim::Genome best = Optimise(SnakeProblem(robust));
    const auto [nominal, perturbed] = Replay(best);
    const double s = nominal > 0 ? perturbed / nominal : 0.0;
    share[robust > 0] = s;
    std::string genes;
    for (double v : best) genes += fmt::format(" {:.3f}", v);
    std::printf(
        "%s gait:%s  nominal %.3f m, mean of %d perturbed worlds %.3f m "
        "(keeps %.2f)\n",
        robust > 0 ? "robust (--robust 8)" : "nominal", genes.c_str(), nominal,
        kReplayWorlds, perturbed, s);
    std::fflush(stdout);
  }
  std::printf("BENCH robust_gap %.2f x\n",
              share[0] > 0 ? share[1] / share[0] : 0.0);
  return 0;
}
