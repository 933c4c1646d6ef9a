// An optimisation algorithm in ask/tell form: Ask gives a generation to
// evaluate as one batch, Tell gives back the results in the same order.
// All randomness comes from one Random seeded with settings.seed, so the
// same settings and the same results give the same generations.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/enum_table.h"
#include "optimizer/search/algorithm_registry.h"
#include "optimizer/search/eval_result.h"
#include "optimizer/search/genome.h"

namespace mrsim {

// How the genetic algorithm picks parents.
enum class SelectionMethod { kTournament, kTruncation };
const EnumTable<SelectionMethod>& SelectionMethods();
inline const char* ToString(SelectionMethod method) {
  return SelectionMethods().Name(method);
}
// Throws std::invalid_argument naming `field` and every valid word.
inline SelectionMethod ParseSelectionMethod(
    const std::string& text, const std::string& field = "selection") {
  return SelectionMethods().Parse(text, field);
}

struct AlgorithmSettings {
  static constexpr int kMaxIslands = 16;
  AlgorithmKind algorithm = AlgorithmKind::kGa;  // see Algorithms()
  int population = 16;
  std::uint64_t seed = 1;
  bool include_start = true;  // generation 0 holds the start genome
  // Independent populations whose generations take turns (generation k is
  // island k % islands's): each island's next generation is asked while
  // the others' are evaluated, so a farm never waits for a generation's
  // slowest episode. Island 0 is the run with `seed`; the others have
  // seeds of their own. 1: one population, every generation waits.
  int islands = 1;

  // Genetic algorithm.
  SelectionMethod selection = SelectionMethod::kTournament;
  int tournament_size = 3;
  double truncation_fraction = 0.5;  // best fraction that may breed
  double crossover_rate = 0.9;       // else the child copies one parent
  double mutation_rate = 0.2;        // per gene
  double mutation_scale = 0.1;       // step std dev, fraction of the range
  int elites = 1;                    // best individuals copied unchanged

  // Simulated annealing (population = number of parallel chains).
  double sa_t0 = 0.0;       // start temperature; <= 0: 0.1 x std dev of gen 0
  double sa_cooling = 0.9;  // T *= cooling every generation
  double sa_rate = 0.5;     // per-gene probability of a move
  double sa_step = 0.1;     // move std dev, fraction of the range

  // Particle swarm (Clerc constriction defaults).
  double pso_inertia = 0.7298;
  double pso_c1 = 1.49618;
  double pso_c2 = 1.49618;
  double pso_vmax = 0.5;  // velocity limit, fraction of the range

  // CMA-ES (population = lambda; the best half is recombined).
  double cmaes_sigma = 0.3;  // start step size, fraction of the range

  // Throws std::invalid_argument naming the setting.
  void Validate() const;
  // Every setting as "key=value" lines (checkpoint fingerprint, logs).
  std::string Describe() const;
};

class Algorithm {
 public:
  virtual ~Algorithm() = default;
  virtual std::vector<Genome> Ask() = 0;
  // Throws std::invalid_argument when the count does not match Ask.
  virtual void Tell(const std::vector<EvalResult>& results) = 0;
};

// The seed of island `island` (island 0: `seed` itself).
std::uint64_t IslandSeed(std::uint64_t seed, int island);

// The algorithm settings.algorithm names (its row of Algorithms()).
std::unique_ptr<Algorithm> MakeAlgorithm(const GenomeSpec& spec,
                                         const AlgorithmSettings& settings);

}  // namespace mrsim
