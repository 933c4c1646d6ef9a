#include "optimizer/search/cmaes.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/search/test_functions.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

RunResult RunTest(const std::string& algo, const std::string& function,
                  std::uint64_t seed, int population, int generations,
                  BatchEvaluator* evaluator = nullptr,
                  const std::string& out_dir = "") {
  const GenomeSpec spec = TestFunctionSpec(6, -5.12, 5.12, 4.0);
  AlgorithmSettings settings;
  settings.algorithm = ParseAlgorithm(algo);
  settings.population = population;
  settings.seed = seed;
  LocalEvaluator local(
      [&](const Genome& g) { return EvaluateTestFunction(function, g); }, 1);
  OptimizationRunOptions options;
  options.generations = generations;
  options.out_dir = out_dir;
  return RunOptimization(spec, settings, evaluator ? *evaluator : local,
                         options);
}

TEST(OptimizerCmaes, BeatsRandomSearchAtEqualBudgetOnSphereAndRastrigin) {
  for (const std::string function : {"sphere", "rastrigin"}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const double cmaes =
          RunTest("cmaes", function, seed, 20, 30).best_result.fitness;
      const double random =
          RunTest("random", function, seed, 20, 30).best_result.fitness;
      EXPECT_GT(cmaes, random) << function << " seed " << seed;
    }
  }
}

TEST(OptimizerCmaes, ConvergesOnTheSphere) {
  // 6-D sphere from x = 4: CMA-ES must close in on the optimum, not just
  // beat random sampling.
  EXPECT_GT(RunTest("cmaes", "sphere", 3, 12, 120).best_result.fitness, -1e-6);
}

TEST(OptimizerCmaes, StaysWithinTheLimitsAndKeepsDisabledGenes) {
  GenomeSpec spec = TestFunctionSpec(4, -1, 1, 0.9);
  spec.genes[2].enabled = false;
  AlgorithmSettings settings;
  settings.algorithm = AlgorithmKind::kCmaes;
  settings.population = 10;
  settings.cmaes_sigma = 1.0;  // large steps hit the limits often
  Cmaes cmaes(spec, settings);
  for (int gen = 0; gen < 20; ++gen) {
    const std::vector<Genome> batch = cmaes.Ask();
    ASSERT_EQ(batch.size(), 10u);
    std::vector<EvalResult> results;
    for (const Genome& g : batch) {
      for (int i = 0; i < 4; ++i) {
        EXPECT_GE(g[i], -1.0);
        EXPECT_LE(g[i], 1.0);
      }
      EXPECT_EQ(g[2], 0.9);
      results.push_back(EvaluateTestFunction("sphere", g));
    }
    cmaes.Tell(results);
  }
  EXPECT_LT(cmaes.sigma(), 1.0);  // it adapted its step
}

TEST(OptimizerCmaes, AskedTwiceGivesTheSameGenerationAndTellChecksTheCount) {
  const GenomeSpec spec = TestFunctionSpec(3, -1, 1, 0.5);
  AlgorithmSettings settings;
  settings.algorithm = AlgorithmKind::kCmaes;
  settings.population = 6;
  Cmaes cmaes(spec, settings);
  const auto first = cmaes.Ask();
  EXPECT_EQ(first[0], spec.StartGenome());  // generation 0 holds the start
  EXPECT_EQ(cmaes.Ask(), first);
  EXPECT_THROW(cmaes.Tell(std::vector<EvalResult>(5)), std::invalid_argument);
}

struct StoppingEvaluator : BatchEvaluator {
  int stop_at = -1;
  int batches = 0;
  std::vector<EvalResult> Evaluate(const std::vector<Genome>& batch) override {
    if (batches++ == stop_at) throw EvaluationInterrupted("killed");
    std::vector<EvalResult> r;
    for (const Genome& g : batch) {
      r.push_back(EvaluateTestFunction("rastrigin", g));
    }
    return r;
  }
};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OptimizerCmaes, ResumeAfterKillIsBitIdentical) {
  const std::string straight_dir = testing::TempDir("cmaes_straight");
  const std::string resumed_dir = testing::TempDir("cmaes_resumed");
  StoppingEvaluator straight;
  const RunResult a =
      RunTest("cmaes", "rastrigin", 4, 8, 15, &straight, straight_dir);
  StoppingEvaluator killed;
  killed.stop_at = 7;
  EXPECT_THROW(RunTest("cmaes", "rastrigin", 4, 8, 15, &killed, resumed_dir),
               EvaluationInterrupted);
  StoppingEvaluator again;
  const RunResult b =
      RunTest("cmaes", "rastrigin", 4, 8, 15, &again, resumed_dir);
  EXPECT_EQ(b.generations_replayed, 7);
  EXPECT_EQ(a.best, b.best);
  EXPECT_EQ(a.best_result.fitness, b.best_result.fitness);
  for (const char* f :
       {"/generations.csv", "/evaluations.csv", "/checkpoint.txt"}) {
    EXPECT_EQ(ReadAll(resumed_dir + f), ReadAll(straight_dir + f)) << f;
  }
}

}  // namespace
}  // namespace mrsim
