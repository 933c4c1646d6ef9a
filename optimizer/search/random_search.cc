#include "optimizer/search/random_search.h"

namespace mrsim {

RandomSearch::RandomSearch(const GenomeSpec& spec,
                           const AlgorithmSettings& settings)
    : spec_(spec), settings_(settings), random_(settings.seed) {}

std::vector<Genome> RandomSearch::Ask() {
  if (!told_) return current_;
  current_.clear();
  for (int i = 0; i < settings_.population; ++i) {
    current_.push_back(first_ && i == 0 && settings_.include_start
                           ? spec_.StartGenome()
                           : spec_.RandomGenome(random_));
  }
  first_ = false;
  told_ = false;
  return current_;
}

void RandomSearch::Tell(const std::vector<EvalResult>& results) {
  if (results.size() != current_.size()) {
    throw std::invalid_argument(
        "random search: results do not match the generation");
  }
  told_ = true;
}

}  // namespace mrsim
