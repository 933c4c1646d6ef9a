// Generational GA: elitism, tournament or truncation selection, uniform
// crossover and clamped normal mutation (optimizer/search/operators.h).
#pragma once

#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/random.h"

namespace mrsim {

class GeneticAlgorithm : public Algorithm {
 public:
  GeneticAlgorithm(const GenomeSpec& spec, const AlgorithmSettings& settings);
  std::vector<Genome> Ask() override;
  void Tell(const std::vector<EvalResult>& results) override;

 private:
  GenomeSpec spec_;
  AlgorithmSettings settings_;
  Random random_;
  std::vector<Genome> population_;
  std::vector<double> fitness_;
  bool told_ = false;
};

}  // namespace mrsim
