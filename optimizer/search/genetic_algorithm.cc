#include "optimizer/search/genetic_algorithm.h"

#include "optimizer/search/operators.h"

namespace mrsim {

GeneticAlgorithm::GeneticAlgorithm(const GenomeSpec& spec,
                                   const AlgorithmSettings& settings)
    : spec_(spec), settings_(settings), random_(settings.seed) {}

std::vector<Genome> GeneticAlgorithm::Ask() {
  const int n = settings_.population;
  if (population_.empty()) {
    for (int i = 0; i < n; ++i) {
      population_.push_back(i == 0 && settings_.include_start
                                ? spec_.StartGenome()
                                : spec_.RandomGenome(random_));
    }
    return population_;
  }
  if (!told_) return population_;  // asked twice: same generation
  const std::vector<int> ranking = RankByFitness(fitness_);
  std::vector<Genome> next;
  for (int e = 0; e < settings_.elites && e < n; ++e) {
    next.push_back(population_[ranking[e]]);
  }
  auto select = [&]() {
    return settings_.selection == SelectionMethod::kTruncation
               ? TruncationSelect(ranking, settings_.truncation_fraction,
                                  random_)
               : TournamentSelect(fitness_, settings_.tournament_size, random_);
  };
  while (static_cast<int>(next.size()) < n) {
    const int a = select();
    const int b = select();
    Genome child =
        random_.Bernoulli(settings_.crossover_rate)
            ? UniformCrossover(spec_, population_[a], population_[b], random_)
            : population_[a];
    Mutate(spec_, child, settings_.mutation_rate, settings_.mutation_scale,
           random_);
    next.push_back(std::move(child));
  }
  population_ = std::move(next);
  told_ = false;
  return population_;
}

void GeneticAlgorithm::Tell(const std::vector<EvalResult>& results) {
  if (results.size() != population_.size()) {
    throw std::invalid_argument("GA: results do not match the generation");
  }
  fitness_.clear();
  for (const EvalResult& r : results) fitness_.push_back(r.fitness);
  told_ = true;
}

}  // namespace mrsim
