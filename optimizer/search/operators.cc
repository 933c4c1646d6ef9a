#include "optimizer/search/operators.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mrsim {

Genome UniformCrossover(const GenomeSpec& spec, const Genome& a,
                        const Genome& b, Random& random) {
  Genome child(a.size());
  for (int i = 0; i < spec.size(); ++i) {
    // Draw for every gene, enabled or not, so toggling a gene off does not
    // shift the random stream of the others.
    const bool from_a = random.Bernoulli(0.5);
    child[i] = spec.Legal(i, from_a ? a[i] : b[i]);
  }
  return child;
}

void Mutate(const GenomeSpec& spec, Genome& genome, double rate, double scale,
            Random& random) {
  for (int i = 0; i < spec.size(); ++i) {
    const bool hit = random.Bernoulli(rate);
    const double step = random.Normal();
    const GeneSpec& gene = spec.genes[i];
    if (!gene.enabled || !hit) {
      genome[i] = spec.Legal(i, genome[i]);
      continue;
    }
    double delta = step * scale * (gene.upper - gene.lower);
    if (gene.integer) {
      delta = std::round(delta);
      if (delta == 0) delta = step < 0 ? -1 : 1;
    }
    genome[i] = spec.Legal(i, genome[i] + delta);
  }
}

std::vector<int> RankByFitness(const std::vector<double>& fitness) {
  std::vector<int> order(fitness.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return fitness[x] > fitness[y]; });
  return order;
}

int TournamentSelect(const std::vector<double>& fitness, int k,
                     Random& random) {
  const long long n = static_cast<long long>(fitness.size());
  int best = -1;
  for (int j = 0; j < std::max(1, k); ++j) {
    const int c = static_cast<int>(random.UniformInt(0, n - 1));
    if (best < 0 || fitness[c] > fitness[best] ||
        (fitness[c] == fitness[best] && c < best)) {
      best = c;
    }
  }
  return best;
}

int TruncationSelect(const std::vector<int>& ranking, double fraction,
                     Random& random) {
  const long long n = static_cast<long long>(ranking.size());
  long long top = static_cast<long long>(std::ceil(fraction * n));
  top = std::clamp<long long>(top, 1, n);
  return ranking[random.UniformInt(0, top - 1)];
}

}  // namespace mrsim
