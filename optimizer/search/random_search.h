// The baseline: every generation is uniformly random within the limits.
#pragma once

#include "optimizer/search/algorithm.h"
#include "optimizer/search/random.h"

namespace mrsim {

class RandomSearch : public Algorithm {
 public:
  RandomSearch(const GenomeSpec& spec, const AlgorithmSettings& settings);
  std::vector<Genome> Ask() override;
  void Tell(const std::vector<EvalResult>& results) override;

 private:
  GenomeSpec spec_;
  AlgorithmSettings settings_;
  Random random_;
  std::vector<Genome> current_;
  bool told_ = true;
  bool first_ = true;
};

}  // namespace mrsim
