#include "optimizer/search/simulated_annealing.h"

#include <cmath>

#include "optimizer/search/operators.h"

namespace mrsim {

SimulatedAnnealing::SimulatedAnnealing(const GenomeSpec& spec,
                                       const AlgorithmSettings& settings)
    : spec_(spec), settings_(settings), random_(settings.seed) {}

std::vector<Genome> SimulatedAnnealing::Ask() {
  if (!told_) return proposed_;
  proposed_.clear();
  if (current_.empty()) {
    for (int i = 0; i < settings_.population; ++i) {
      proposed_.push_back(i == 0 && settings_.include_start
                              ? spec_.StartGenome()
                              : spec_.RandomGenome(random_));
    }
  } else {
    for (const Genome& g : current_) {
      Genome n = g;
      Mutate(spec_, n, settings_.sa_rate, settings_.sa_step, random_);
      proposed_.push_back(std::move(n));
    }
  }
  told_ = false;
  return proposed_;
}

void SimulatedAnnealing::Tell(const std::vector<EvalResult>& results) {
  if (results.size() != proposed_.size()) {
    throw std::invalid_argument("SA: results do not match the generation");
  }
  told_ = true;
  if (current_.empty()) {
    current_ = proposed_;
    double mean = 0;
    for (const EvalResult& r : results) {
      current_fitness_.push_back(r.fitness);
      mean += r.fitness;
    }
    mean /= results.size();
    double var = 0;
    for (const EvalResult& r : results) {
      var += (r.fitness - mean) * (r.fitness - mean);
    }
    const double spread = std::sqrt(var / results.size());
    temperature_ =
        settings_.sa_t0 > 0
            ? settings_.sa_t0
            : (std::isfinite(spread) && spread > 0 ? 0.1 * spread : 1.0);
    return;
  }
  for (size_t c = 0; c < current_.size(); ++c) {
    const double u = random_.Uniform01();  // drawn always: a stable stream
    const double delta = results[c].fitness - current_fitness_[c];
    if (delta >= 0 || u < std::exp(delta / temperature_)) {
      current_[c] = proposed_[c];
      current_fitness_[c] = results[c].fitness;
    }
  }
  temperature_ *= settings_.sa_cooling;
}

}  // namespace mrsim
