// Simulated annealing as parallel chains: each generation every chain
// proposes one neighbour (the batch); a worse one is accepted with
// probability exp((f_new - f_old) / T) (we maximise), T falls geometrically.
#pragma once

#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/random.h"

namespace mrsim {

class SimulatedAnnealing : public Algorithm {
 public:
  SimulatedAnnealing(const GenomeSpec& spec, const AlgorithmSettings& settings);
  std::vector<Genome> Ask() override;
  void Tell(const std::vector<EvalResult>& results) override;

  double temperature() const { return temperature_; }

 private:
  GenomeSpec spec_;
  AlgorithmSettings settings_;
  Random random_;
  std::vector<Genome> current_;
  std::vector<double> current_fitness_;
  std::vector<Genome> proposed_;
  double temperature_ = 0.0;
  bool told_ = true;
};

}  // namespace mrsim
