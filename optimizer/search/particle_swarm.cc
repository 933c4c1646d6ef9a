#include "optimizer/search/particle_swarm.h"

#include <algorithm>

namespace mrsim {

ParticleSwarm::ParticleSwarm(const GenomeSpec& spec,
                             const AlgorithmSettings& settings)
    : spec_(spec), settings_(settings), random_(settings.seed) {}

std::vector<Genome> ParticleSwarm::Ask() {
  if (!told_) return position_;
  const int dims = spec_.size();
  if (!started_) {
    for (int i = 0; i < settings_.population; ++i) {
      position_.push_back(i == 0 && settings_.include_start
                              ? spec_.StartGenome()
                              : spec_.RandomGenome(random_));
      std::vector<double> v(dims, 0.0);
      for (int d = 0; d < dims; ++d) {
        const GeneSpec& g = spec_.genes[d];
        const double r = random_.Uniform(-1.0, 1.0);
        if (g.enabled) v[d] = 0.1 * r * (g.upper - g.lower);
      }
      velocity_.push_back(v);
    }
    started_ = true;
  } else {
    for (size_t i = 0; i < position_.size(); ++i) {
      for (int d = 0; d < dims; ++d) {
        const double r1 = random_.Uniform01();
        const double r2 = random_.Uniform01();
        const GeneSpec& g = spec_.genes[d];
        if (!g.enabled) continue;
        const double vmax = settings_.pso_vmax * (g.upper - g.lower);
        double& v = velocity_[i][d];
        double& x = position_[i][d];
        v = settings_.pso_inertia * v +
            settings_.pso_c1 * r1 * (personal_best_[i][d] - x) +
            settings_.pso_c2 * r2 * (global_best_[d] - x);
        v = std::clamp(v, -vmax, vmax);
        const double moved = x + v;
        x = spec_.Legal(d, moved);
        if (x != moved && !g.integer) v = 0.0;  // stopped by a limit
      }
    }
  }
  told_ = false;
  return position_;
}

void ParticleSwarm::Tell(const std::vector<EvalResult>& results) {
  if (results.size() != position_.size()) {
    throw std::invalid_argument("PSO: results do not match the generation");
  }
  told_ = true;
  const bool first = personal_best_.empty();
  for (size_t i = 0; i < position_.size(); ++i) {
    const double f = results[i].fitness;
    if (first || f > personal_best_fitness_[i]) {
      if (first) {
        personal_best_.push_back(position_[i]);
        personal_best_fitness_.push_back(f);
      } else {
        personal_best_[i] = position_[i];
        personal_best_fitness_[i] = f;
      }
    }
    if ((first && i == 0) || f > global_best_fitness_) {
      global_best_ = position_[i];
      global_best_fitness_ = f;
    }
  }
}

}  // namespace mrsim
