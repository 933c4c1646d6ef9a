#include <gtest/gtest.h>

#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/search/test_functions.h"

namespace mrsim {
namespace {

double BestOf(const std::string& algo, const std::string& function,
              std::uint64_t seed, int population, int generations) {
  const GenomeSpec spec = TestFunctionSpec(6, -5.12, 5.12, 4.0);
  AlgorithmSettings settings;
  settings.algorithm = ParseAlgorithm(algo);
  settings.population = population;
  settings.seed = seed;
  LocalEvaluator evaluator(
      [&](const Genome& g) { return EvaluateTestFunction(function, g); }, 1);
  OptimizationRunOptions options;
  options.generations = generations;
  return RunOptimization(spec, settings, evaluator, options)
      .best_result.fitness;
}

TEST(OptimizerAlgorithms, GeneticAlgorithmBeatsRandomSearchAtEqualBudget) {
  for (const std::string function : {"sphere", "rastrigin"}) {
    int ga_wins = 0;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const double ga = BestOf("ga", function, seed, 20, 30);
      const double random = BestOf("random", function, seed, 20, 30);
      ga_wins += ga > random;
    }
    EXPECT_EQ(ga_wins, 5) << function;
  }
}

TEST(OptimizerAlgorithms, AnnealingAndSwarmBeatRandomSearchOnSphere) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const double random = BestOf("random", "sphere", seed, 20, 30);
    EXPECT_GT(BestOf("sa", "sphere", seed, 20, 30), random) << seed;
    EXPECT_GT(BestOf("pso", "sphere", seed, 20, 30), random) << seed;
  }
}

TEST(OptimizerAlgorithms, ResultDoesNotDependOnThreadCount) {
  const GenomeSpec spec = TestFunctionSpec(5, -5.12, 5.12, 4.0);
  for (const std::string algo : {"ga", "sa", "pso", "cmaes", "random"}) {
    AlgorithmSettings settings;
    settings.algorithm = ParseAlgorithm(algo);
    settings.population = 9;
    settings.seed = 5;
    OptimizationRunOptions options;
    options.generations = 12;
    auto fn = [](const Genome& g) {
      return EvaluateTestFunction("rastrigin", g);
    };
    LocalEvaluator one(fn, 1), four(fn, 4);
    const RunResult a = RunOptimization(spec, settings, one, options);
    const RunResult b = RunOptimization(spec, settings, four, options);
    EXPECT_EQ(a.best, b.best) << algo;
    EXPECT_EQ(a.best_result.fitness, b.best_result.fitness) << algo;
    settings.seed = 6;
    const RunResult c = RunOptimization(spec, settings, one, options);
    EXPECT_NE(a.best, c.best) << algo << ": the seed must matter";
  }
}

}  // namespace
}  // namespace mrsim
