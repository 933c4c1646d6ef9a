#include "optimizer/search/algorithm.h"

#include <fmt/format.h>

namespace mrsim {

const EnumTable<SelectionMethod>& SelectionMethods() {
  static const EnumTable<SelectionMethod> kMethods(
      "selection", {{SelectionMethod::kTournament, "tournament"},
                    {SelectionMethod::kTruncation, "truncation"}});
  return kMethods;
}

void AlgorithmSettings::Validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument(what);
  };
  // A value cast from a number, not one of the registry's.
  AlgorithmNames().Parse(ToString(algorithm));
  if (population < 1) fail("population must be at least 1");
  if (islands < 1 || islands > kMaxIslands) {
    fail(fmt::format("islands must be in [1, {}]", kMaxIslands));
  }
  SelectionMethods().Parse(ToString(selection));
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
  const AlgorithmInfo& info = AlgorithmInfoOf(algorithm);
  if (population < info.min_population) {
    fail(fmt::format("{} needs a population of at least {}", info.title,
                     info.min_population));
  }
}

std::string AlgorithmSettings::Describe() const {
  std::string s =
      fmt::format("algorithm={}\npopulation={}\nseed={}\ninclude_start={}\n",
                  ToString(algorithm), population, seed, include_start);
  // Not written when 1, so runs from before islands keep their checkpoints.
  if (islands != 1) s += fmt::format("islands={}\n", islands);
  // Each algorithm's own settings only, so a checkpoint's fingerprint does
  // not change with settings the run does not use.
  if (algorithm == AlgorithmKind::kGa) {
    s += fmt::format(
        "selection={}\ntournament_size={}\ntruncation_fraction={}\n"
        "crossover_rate={}\nmutation_rate={}\nmutation_scale={}\nelites={}\n",
        ToString(selection), tournament_size, truncation_fraction,
        crossover_rate, mutation_rate, mutation_scale, elites);
  } else if (algorithm == AlgorithmKind::kSa) {
    s += fmt::format("sa_t0={}\nsa_cooling={}\nsa_rate={}\nsa_step={}\n", sa_t0,
                     sa_cooling, sa_rate, sa_step);
  } else if (algorithm == AlgorithmKind::kPso) {
    s += fmt::format("pso_inertia={}\npso_c1={}\npso_c2={}\npso_vmax={}\n",
                     pso_inertia, pso_c1, pso_c2, pso_vmax);
  } else if (algorithm == AlgorithmKind::kCmaes) {
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
  return AlgorithmInfoOf(settings.algorithm).make(spec, settings);
}

}  // namespace mrsim
