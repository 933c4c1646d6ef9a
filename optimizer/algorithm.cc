#include "optimizer/algorithm.h"

#include <fmt/format.h>

#include "optimizer/cmaes.h"
#include "optimizer/genetic_algorithm.h"
#include "optimizer/particle_swarm.h"
#include "optimizer/random_search.h"
#include "optimizer/simulated_annealing.h"

namespace mrsim {

void AlgorithmSettings::Validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument(what);
  };
  if (algorithm != "ga" && algorithm != "sa" && algorithm != "pso" &&
      algorithm != "cmaes" && algorithm != "random") {
    fail("algorithm: expected ga, sa, pso, cmaes or random, got '" + algorithm +
         "'");
  }
  if (population < 1) fail("population must be at least 1");
  if (islands < 1 || islands > kMaxIslands) {
    fail(fmt::format("islands must be in [1, {}]", kMaxIslands));
  }
  if (selection != "tournament" && selection != "truncation") {
    fail("selection: expected tournament or truncation, got '" + selection +
         "'");
  }
  if (tournament_size < 1) fail("tournament size must be at least 1");
  if (!(truncation_fraction > 0 && truncation_fraction <= 1)) {
    fail("truncation fraction must be in (0, 1]");
  }
  if (!(crossover_rate >= 0 && crossover_rate <= 1)) {
    fail("crossover rate must be in [0, 1]");
  }
  if (!(mutation_rate >= 0 && mutation_rate <= 1)) {
    fail("mutation rate must be in [0, 1]");
  }
  if (!(mutation_scale >= 0)) fail("mutation scale must be >= 0");
  if (elites < 0 || elites > population) {
    fail("elites must be in [0, population]");
  }
  if (!(sa_cooling > 0 && sa_cooling <= 1)) {
    fail("SA cooling must be in (0, 1]");
  }
  if (!(sa_rate >= 0 && sa_rate <= 1)) fail("SA rate must be in [0, 1]");
  if (!(sa_step >= 0)) fail("SA step must be >= 0");
  if (!(pso_vmax > 0)) fail("PSO vmax must be > 0");
  if (!(cmaes_sigma > 0 && cmaes_sigma <= 1)) {
    fail("CMA-ES sigma must be in (0, 1]");
  }
  if (algorithm == "cmaes" && population < 2) {
    fail("CMA-ES needs a population of at least 2");
  }
}

std::string AlgorithmSettings::Describe() const {
  std::string s =
      fmt::format("algorithm={}\npopulation={}\nseed={}\ninclude_start={}\n",
                  algorithm, population, seed, include_start);
  // Not written when 1, so runs from before islands keep their checkpoints.
  if (islands != 1) s += fmt::format("islands={}\n", islands);
  if (algorithm == "ga") {
    s += fmt::format(
        "selection={}\ntournament_size={}\ntruncation_fraction={}\n"
        "crossover_rate={}\nmutation_rate={}\nmutation_scale={}\nelites={}\n",
        selection, tournament_size, truncation_fraction, crossover_rate,
        mutation_rate, mutation_scale, elites);
  } else if (algorithm == "sa") {
    s += fmt::format("sa_t0={}\nsa_cooling={}\nsa_rate={}\nsa_step={}\n", sa_t0,
                     sa_cooling, sa_rate, sa_step);
  } else if (algorithm == "pso") {
    s += fmt::format("pso_inertia={}\npso_c1={}\npso_c2={}\npso_vmax={}\n",
                     pso_inertia, pso_c1, pso_c2, pso_vmax);
  } else if (algorithm == "cmaes") {
    s += fmt::format("cmaes_sigma={}\n", cmaes_sigma);
  }
  return s;
}

std::uint64_t IslandSeed(std::uint64_t seed, int island) {
  if (island == 0) return seed;
  // SplitMix64's step: island seeds far from seed + 1, seed + 2 (another
  // run's island 0).
  std::uint64_t z =
      seed + 0x9E3779B97F4A7C15ull * static_cast<unsigned>(island);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::unique_ptr<Algorithm> MakeAlgorithm(const GenomeSpec& spec,
                                         const AlgorithmSettings& settings) {
  settings.Validate();
  if (settings.algorithm == "ga") {
    return std::make_unique<GeneticAlgorithm>(spec, settings);
  }
  if (settings.algorithm == "sa") {
    return std::make_unique<SimulatedAnnealing>(spec, settings);
  }
  if (settings.algorithm == "pso") {
    return std::make_unique<ParticleSwarm>(spec, settings);
  }
  if (settings.algorithm == "cmaes") {
    return std::make_unique<Cmaes>(spec, settings);
  }
  return std::make_unique<RandomSearch>(spec, settings);
}

}  // namespace mrsim
