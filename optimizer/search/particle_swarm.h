// Particle swarm optimisation (global-best topology, constriction
// coefficients). Written here rather than taken from pagmo so that it runs
// one generation per batch with our seeded Random and our evaluators (see
// docs/optimizer.md).
#pragma once

#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/random.h"

namespace mrsim {

class ParticleSwarm : public Algorithm {
 public:
  ParticleSwarm(const GenomeSpec& spec, const AlgorithmSettings& settings);
  std::vector<Genome> Ask() override;
  void Tell(const std::vector<EvalResult>& results) override;

 private:
  GenomeSpec spec_;
  AlgorithmSettings settings_;
  Random random_;
  std::vector<Genome> position_;
  std::vector<std::vector<double>> velocity_;
  std::vector<Genome> personal_best_;
  std::vector<double> personal_best_fitness_;
  Genome global_best_;
  double global_best_fitness_ = 0.0;
  bool told_ = true;
  bool started_ = false;
};

}  // namespace mrsim
