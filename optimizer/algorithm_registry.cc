#include "optimizer/algorithm_registry.h"

#include <stdexcept>

#include "optimizer/algorithm.h"
#include "optimizer/cmaes.h"
#include "optimizer/genetic_algorithm.h"
#include "optimizer/particle_swarm.h"
#include "optimizer/random_search.h"
#include "optimizer/simulated_annealing.h"

namespace mrsim {
namespace {

template <typename T>
std::unique_ptr<Algorithm> Make(const GenomeSpec& spec,
                                const AlgorithmSettings& settings) {
  return std::make_unique<T>(spec, settings);
}

}  // namespace

const std::vector<AlgorithmInfo>& Algorithms() {
  static const std::vector<AlgorithmInfo> kAlgorithms = {
      {AlgorithmKind::kGa, "ga", "the genetic algorithm",
       "genetic algorithm: elitism, tournament or truncation selection, "
       "uniform crossover, normal mutation",
       1, &Make<GeneticAlgorithm>},
      {AlgorithmKind::kSa, "sa", "simulated annealing",
       "simulated annealing as --population parallel chains", 1,
       &Make<SimulatedAnnealing>},
      {AlgorithmKind::kPso, "pso", "the particle swarm",
       "particle swarm, global best, constriction coefficients", 1,
       &Make<ParticleSwarm>},
      {AlgorithmKind::kCmaes, "cmaes", "CMA-ES",
       "CMA-ES: adapts a normal distribution's mean, covariance and step", 2,
       &Make<Cmaes>},
      {AlgorithmKind::kRandom, "random", "random search",
       "uniform samples within the limits (the baseline)", 1,
       &Make<RandomSearch>},
  };
  return kAlgorithms;
}

const AlgorithmInfo& AlgorithmInfoOf(AlgorithmKind kind) {
  for (const AlgorithmInfo& info : Algorithms()) {
    if (info.kind == kind) return info;
  }
  throw std::invalid_argument("algorithm: value " +
                              std::to_string(static_cast<int>(kind)) +
                              " is not in the registry");
}

int AlgorithmIndex(AlgorithmKind kind) {
  return static_cast<int>(&AlgorithmInfoOf(kind) - Algorithms().data());
}

const EnumTable<AlgorithmKind>& AlgorithmNames() {
  static const EnumTable<AlgorithmKind> kNames = [] {
    std::vector<EnumTable<AlgorithmKind>::Entry> entries;
    for (const AlgorithmInfo& info : Algorithms()) {
      entries.push_back({info.kind, info.name});
    }
    return EnumTable<AlgorithmKind>("algorithm", std::move(entries));
  }();
  return kNames;
}

}  // namespace mrsim
