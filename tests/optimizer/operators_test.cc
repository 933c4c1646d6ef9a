#include "optimizer/search/operators.h"

#include <gtest/gtest.h>

#include "optimizer/search/genetic_algorithm.h"
#include "optimizer/search/test_functions.h"

namespace mrsim {
namespace {

GenomeSpec MixedSpec() {
  GenomeSpec spec = TestFunctionSpec(6, -2.0, 3.0, 0.5);
  spec.genes[2].enabled = false;  // toggled off: keeps 0.5
  spec.genes[4].integer = true;
  spec.genes[4].lower = -3;
  spec.genes[4].upper = 7;
  spec.genes[4].start = 1;
  spec.Validate("test");
  return spec;
}

TEST(OptimizerOperators, UniformCrossoverTakesEachGeneFromOneParent) {
  GenomeSpec spec = TestFunctionSpec(20, -1.0, 1.0, 0.0);
  Random random(7);
  const Genome a = spec.RandomGenome(random);
  const Genome b = spec.RandomGenome(random);
  int from_a = 0, from_b = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Genome c = UniformCrossover(spec, a, b, random);
    ASSERT_EQ(c.size(), a.size());
    for (size_t i = 0; i < c.size(); ++i) {
      ASSERT_TRUE(c[i] == a[i] || c[i] == b[i]) << "gene " << i;
      from_a += c[i] == a[i];
      from_b += c[i] == b[i];
    }
  }
  // Both parents contribute (uniform, not one-point or a copy).
  EXPECT_GT(from_a, 300);
  EXPECT_GT(from_b, 300);
}

TEST(OptimizerOperators, MutationStaysWithinLimits) {
  const GenomeSpec spec = MixedSpec();
  Random random(3);
  Genome g = spec.StartGenome();
  bool moved = false;
  for (int trial = 0; trial < 2000; ++trial) {
    const Genome before = g;
    Mutate(spec, g, 0.5, 2.0, random);  // huge steps hit the limits
    EXPECT_NO_THROW(spec.Check(g));
    for (int i = 0; i < spec.size(); ++i) {
      ASSERT_GE(g[i], spec.genes[i].lower);
      ASSERT_LE(g[i], spec.genes[i].upper);
    }
    EXPECT_EQ(g[4], std::round(g[4]));
    moved = moved || before != g;
  }
  EXPECT_TRUE(moved);
}

TEST(OptimizerOperators, ToggledOffGenesNeverChange) {
  const GenomeSpec spec = MixedSpec();
  AlgorithmSettings settings;
  settings.population = 12;
  settings.mutation_rate = 1.0;
  settings.mutation_scale = 0.5;
  for (const std::string algo : {"ga", "sa", "pso", "random"}) {
    settings.algorithm = ParseAlgorithm(algo);
    auto algorithm = MakeAlgorithm(spec, settings);
    for (int gen = 0; gen < 8; ++gen) {
      const std::vector<Genome> batch = algorithm->Ask();
      std::vector<EvalResult> results;
      for (const Genome& g : batch) {
        EXPECT_EQ(g[2], 0.5) << algo << " generation " << gen;
        EXPECT_NO_THROW(spec.Check(g)) << algo;
        results.push_back(EvaluateTestFunction("sphere", g));
      }
      algorithm->Tell(results);
    }
  }
}

TEST(OptimizerOperators, ElitismKeepsTheBest) {
  const GenomeSpec spec = TestFunctionSpec(4, -5.0, 5.0, 3.0);
  AlgorithmSettings settings;
  settings.population = 10;
  settings.elites = 2;
  settings.mutation_rate = 1.0;
  GeneticAlgorithm ga(spec, settings);
  for (int gen = 0; gen < 10; ++gen) {
    const std::vector<Genome> batch = ga.Ask();
    std::vector<EvalResult> results;
    for (const Genome& g : batch) {
      results.push_back(EvaluateTestFunction("sphere", g));
    }
    const std::vector<double> fitness = [&] {
      std::vector<double> f;
      for (const EvalResult& r : results) f.push_back(r.fitness);
      return f;
    }();
    const std::vector<int> rank = RankByFitness(fitness);
    ga.Tell(results);
    const std::vector<Genome> next = ga.Ask();
    EXPECT_EQ(next[0], batch[rank[0]]);
    EXPECT_EQ(next[1], batch[rank[1]]);
    std::vector<EvalResult> next_results;
    for (const Genome& g : next) {
      next_results.push_back(EvaluateTestFunction("sphere", g));
    }
    ga.Tell(next_results);
  }
}

TEST(OptimizerOperators, SelectionPrefersTheFitter) {
  const std::vector<double> fitness = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  const std::vector<int> ranking = RankByFitness(fitness);
  EXPECT_EQ(ranking.front(), 9);
  Random random(11);
  int tournament_sum = 0, truncation_sum = 0;
  for (int i = 0; i < 1000; ++i) {
    tournament_sum += TournamentSelect(fitness, 3, random);
    const int t = TruncationSelect(ranking, 0.3, random);
    EXPECT_GE(t, 7);
    truncation_sum += t;
  }
  EXPECT_GT(tournament_sum / 1000.0, 5.5);  // uniform would give 4.5
  EXPECT_NEAR(truncation_sum / 1000.0, 8.0, 0.2);
}

TEST(OptimizerRandom, SameSeedSameStream) {
  Random a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const double x = a.Uniform01();
    EXPECT_EQ(x, b.Uniform01());
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
  EXPECT_NE(a.Next(), c.Next());
  // mt19937_64's 10000th output is fixed by the standard.
  std::mt19937_64 engine;
  engine.discard(9999);
  EXPECT_EQ(engine(), 9981545732273789042ull);
}

}  // namespace
}  // namespace mrsim
