// BENCH cpg_vs_sine: the best fitness CMA-ES reaches on the flat task with
// the CPG genes (mrsim-opt --genes cpg) over the same with the sine genes
// (--genes sine), same budget and seed, measured in the same run. Also
// prints each best (m in the episode). Budget: population 8, 4
// generations, 10 s episodes, seeds 1 and 2 (the ratio of the means).
#include <fmt/format.h>

#include <cstdlib>
#include <string>

#include "gait_controller/gait_presets.h"
#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/episode/task.h"

namespace {

double BestFitness(const std::string& genes, int seed) {
  const mrsim::Task task = mrsim::MakeTask("flat");
  const mrsim::Problem problem =
      mrsim::TaskProblem(task, *mrsim::FindGaitPreset("forward"),
                         mrsim::BuiltInGenome(genes), 10.0);
  mrsim::AlgorithmSettings a;
  a.algorithm = mrsim::ParseAlgorithm("cmaes");
  a.population = 8;
  a.seed = seed;
  mrsim::LocalEvaluator evaluator(
      [&](const mrsim::Genome& g) { return mrsim::RunEpisode(problem, g); }, 1);
  mrsim::OptimizationRunOptions options;
  options.generations = 4;
  return mrsim::RunOptimization(problem.genome, a, evaluator, options)
      .best_result.fitness;
}

}  // namespace

int main() {
  constexpr int kSeeds = 2;
  double sine = 0, cpg = 0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const double s = BestFitness("sine", seed);
    const double c = BestFitness("cpg", seed);
    fmt::print("seed {}: best sine {:.3f} m, best cpg {:.3f} m\n", seed, s, c);
    std::fflush(stdout);
    sine += s;
    cpg += c;
  }
  fmt::print("BENCH cmaes_flat_sine_best {:.3f} m\n", sine / kSeeds);
  fmt::print("BENCH cmaes_flat_cpg_best {:.3f} m\n", cpg / kSeeds);
  fmt::print("BENCH cpg_vs_sine {:.3f} x\n", cpg / sine);
  return 0;
}
