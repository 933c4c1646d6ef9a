#include "optimizer/search/algorithm_registry.h"

#include <cmath>
#include <stdexcept>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/cmaes.h"
#include "optimizer/search/genetic_algorithm.h"
#include "optimizer/search/particle_swarm.h"
#include "optimizer/search/random_search.h"
#include "optimizer/search/simulated_annealing.h"

namespace mrsim {
namespace {

template <typename T>
std::unique_ptr<Algorithm> Make(const GenomeSpec& spec,
                                const AlgorithmSettings& settings) {
  return std::make_unique<T>(spec, settings);
}

AlgorithmSetting Real(const char* flag, const char* help,
                      double AlgorithmSettings::*value, double min,
                      double max) {
  AlgorithmSetting s{flag, help};
  s.real = value;
  s.min = min;
  s.max = max;
  return s;
}

AlgorithmSetting Whole(const char* flag, const char* help,
                       int AlgorithmSettings::*value, double min, double max) {
  AlgorithmSetting s{flag, help};
  s.whole = value;
  s.min = min;
  s.max = max;
  return s;
}

using S = AlgorithmSettings;

}  // namespace

double AlgorithmSetting::Get(const AlgorithmSettings& s) const {
  return real ? s.*real : static_cast<double>(s.*whole);
}

void AlgorithmSetting::Set(AlgorithmSettings* s, double value) const {
  if (real) {
    s->*real = value;
  } else {
    s->*whole = static_cast<int>(std::lround(value));
  }
}

const AlgorithmSetting* FindAlgorithmSetting(const std::string& flag) {
  for (const AlgorithmInfo& info : Algorithms()) {
    for (const AlgorithmSetting& s : info.settings) {
      if (flag == s.flag) return &s;
    }
  }
  return nullptr;
}

const std::vector<AlgorithmInfo>& Algorithms() {
  static const std::vector<AlgorithmInfo> kAlgorithms = {
      {AlgorithmKind::kGa,
       "ga",
       "the genetic algorithm",
       "genetic algorithm: elitism, tournament or truncation selection, "
       "uniform crossover, normal mutation",
       1,
       &Make<GeneticAlgorithm>,
       {Whole("tournament-size", "GA: individuals per tournament",
              &S::tournament_size, 1, 1000),
        Real("truncation", "GA: best fraction that may breed (truncation)",
             &S::truncation_fraction, 0.01, 1),
        Real("crossover-rate", "GA: chance a child mixes two parents",
             &S::crossover_rate, 0, 1),
        Real("mutation-rate", "GA: per-gene chance of a mutation",
             &S::mutation_rate, 0, 1),
        Real("mutation-scale", "GA: mutation std dev, fraction of the range",
             &S::mutation_scale, 0, 10),
        Whole("elites", "GA: best individuals copied unchanged", &S::elites, 0,
              1000)}},
      {AlgorithmKind::kSa,
       "sa",
       "simulated annealing",
       "simulated annealing as --population parallel chains",
       1,
       &Make<SimulatedAnnealing>,
       {Real("sa-t0", "SA start temperature (0: automatic)", &S::sa_t0, 0,
             1e12),
        Real("sa-cooling", "SA: T *= cooling every generation", &S::sa_cooling,
             0.0001, 1),
        Real("sa-rate", "SA: per-gene chance of a move", &S::sa_rate, 0, 1),
        Real("sa-step", "SA: move std dev, fraction of the range", &S::sa_step,
             0, 10)}},
      {AlgorithmKind::kPso,
       "pso",
       "the particle swarm",
       "particle swarm, global best, constriction coefficients",
       1,
       &Make<ParticleSwarm>,
       {Real("pso-inertia", "PSO: velocity kept each step", &S::pso_inertia, 0,
             10),
        Real("pso-c1", "PSO: pull to the particle's own best", &S::pso_c1, 0,
             10),
        Real("pso-c2", "PSO: pull to the swarm's best", &S::pso_c2, 0, 10),
        Real("pso-vmax", "PSO: velocity limit, fraction of the range",
             &S::pso_vmax, 1e-6, 10)}},
      {AlgorithmKind::kCmaes,
       "cmaes",
       "CMA-ES",
       "CMA-ES: adapts a normal distribution's mean, covariance and step",
       2,
       &Make<Cmaes>,
       {Real("cmaes-sigma", "CMA-ES start step, fraction of each gene's range",
             &S::cmaes_sigma, 1e-6, 1)}},
      {AlgorithmKind::kRandom,
       "random",
       "random search",
       "uniform samples within the limits (the baseline)",
       1,
       &Make<RandomSearch>,
       {}},
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
