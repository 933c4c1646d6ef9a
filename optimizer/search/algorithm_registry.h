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

// One number an algorithm of the registry reads from AlgorithmSettings:
// mrsim-opt's flag (--<flag>) and the studio's field are made from it.
// Exactly one of `real` and `whole` is set.
struct AlgorithmSetting {
  const char* flag;  // "pso-c1": the flag without its dashes
  const char* help;  // one line for help texts and tooltips
  double AlgorithmSettings::*real = nullptr;
  int AlgorithmSettings::*whole = nullptr;
  // The range a form offers (AlgorithmSettings::Validate has the last
  // word, e.g. elites <= population).
  double min = 0;
  double max = 0;

  double Get(const AlgorithmSettings& s) const;
  // Sets the value (rounded for a whole number); no range check.
  void Set(AlgorithmSettings* s, double value) const;
};

struct AlgorithmInfo {
  AlgorithmKind kind;
  const char* name;     // "cmaes": the flag's word and the checkpoint's
  const char* title;    // "CMA-ES": for messages
  const char* summary;  // one line for help texts and the studio
  int min_population;   // AlgorithmSettings::Validate refuses fewer
  std::unique_ptr<Algorithm> (*make)(const GenomeSpec& spec,
                                     const AlgorithmSettings& settings);
  // The settings of its own (AlgorithmSettings), in the order shown.
  std::vector<AlgorithmSetting> settings;
};

// Every algorithm, in the order help texts and menus list them.
const std::vector<AlgorithmInfo>& Algorithms();
// The row of `kind` (throws std::invalid_argument for a value not listed).
const AlgorithmInfo& AlgorithmInfoOf(AlgorithmKind kind);
// The setting whose flag is `flag` ("pso-c1") in any algorithm's row, or
// null.
const AlgorithmSetting* FindAlgorithmSetting(const std::string& flag);
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
