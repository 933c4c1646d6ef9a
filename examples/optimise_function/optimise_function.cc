// mrsim's optimisation algorithms on a fitness function of your own: no
// simulator, no LCM, just the ask/tell loop of mrsim::optimizer. Here the
// function is Rosenbrock's valley in four dimensions (its best, 0, is at
// x = (1, 1, 1, 1)); put your own in Fitness().
//
//   optimise_function [ALGORITHM [GENERATIONS [SEED]]]
//   (ALGORITHM: ga, cmaes, pso, sa or random; default cmaes 60 1)
//
// Prints one line per generation (its best and the best so far) and, last,
// the best genome. The same seed gives the same lines.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/genome.h"

namespace {

// Higher is better in mrsim: the valley's height, negated.
double Fitness(const mrsim::Genome& x) {
  double sum = 0;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    const double a = 1 - x[i];
    const double b = x[i + 1] - x[i] * x[i];
    sum += a * a + 100 * b * b;
  }
  return -sum;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    mrsim::GenomeSpec spec;
    for (int i = 0; i < 4; ++i) {
      // Names are yours: the optimiser only needs limits and a start.
      spec.genes.push_back({"x" + std::to_string(i), -2.0, 2.0, -1.5});
    }
    spec.Validate("optimise_function");
    mrsim::AlgorithmSettings settings;
    settings.algorithm =
        mrsim::ParseAlgorithm(argc > 1 ? argv[1] : "cmaes", "algorithm");
    settings.population = 16;
    settings.seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
    settings.Validate();
    const int generations = argc > 2 ? std::atoi(argv[2]) : 60;
    const auto algorithm = mrsim::MakeAlgorithm(spec, settings);

    double best = -std::numeric_limits<double>::infinity();
    mrsim::Genome best_genome;
    for (int g = 0; g < generations; ++g) {
      const std::vector<mrsim::Genome> batch = algorithm->Ask();
      std::vector<mrsim::EvalResult> results(batch.size());
      double generation_best = -std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < batch.size(); ++i) {
        results[i].fitness = Fitness(batch[i]);
        generation_best = std::max(generation_best, results[i].fitness);
        if (results[i].fitness > best) {
          best = results[i].fitness;
          best_genome = batch[i];
        }
      }
      algorithm->Tell(results);
      std::printf("generation %d of %d: best %.6g, best so far %.6g\n", g + 1,
                  generations, generation_best, best);
    }
    std::printf("best fitness %.6g at x =", best);
    for (double v : best_genome) std::printf(" %.4f", v);
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "optimise_function: %s\n", e.what());
    return 2;
  }
  return 0;
}
