// The optimiser's algorithms, listed once: each row gives the word
// `--algorithm` takes (also written in checkpoints and shown by the
// studio), a one-line summary for help texts, the smallest population it
// runs with and how to build it. mrsim-opt's flag and help, the studio's
// Optimise panel and the test that checks docs/optimizer.md all read this
// list; docs/architecture.md has the recipe for adding a row.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "common/enum_table.h"

namespace mrsim {

class Algorithm;
struct AlgorithmSettings;
struct GenomeSpec;

enum class AlgorithmKind { kGa, kSa, kPso, kCmaes, kRandom };

struct AlgorithmInfo {
  AlgorithmKind kind;
  const char* name;     // "cmaes": the flag's word and the checkpoint's
  const char* title;    // "CMA-ES": for messages
  const char* summary;  // one line for help texts and the studio
  int min_population;   // AlgorithmSettings::Validate refuses fewer
  std::unique_ptr<Algorithm> (*make)(const GenomeSpec& spec,
                                     const AlgorithmSettings& settings);
};

// Every algorithm, in the order help texts and menus list them.
const std::vector<AlgorithmInfo>& Algorithms();
// The row of `kind` (throws std::invalid_argument for a value not listed).
const AlgorithmInfo& AlgorithmInfoOf(AlgorithmKind kind);
// Where `kind`'s row is in Algorithms(), for menus that hold an index (the
// studio's default is AlgorithmIndex(AlgorithmKind::kCmaes), wherever the
// registry lists it). Throws as AlgorithmInfoOf.
int AlgorithmIndex(AlgorithmKind kind);
// The words of the algorithms (built from Algorithms()).
const EnumTable<AlgorithmKind>& AlgorithmNames();

inline const char* ToString(AlgorithmKind kind) {
  return AlgorithmNames().Name(kind);
}
// Throws std::invalid_argument naming `field` and every valid word.
inline AlgorithmKind ParseAlgorithm(const std::string& text,
                                    const std::string& field = "algorithm") {
  return AlgorithmNames().Parse(text, field);
}

}  // namespace mrsim
