// The genome of an optimisation: named genes with limits, a toggle and a
// start value, read from a genome description file (docs/optimizer.md).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimizer/search/random.h"

namespace mrsim {

// Gene names the episode understands: the seven gait parameters in
// GaitParameters order, then the body genes.
inline const std::vector<std::string>& GaitGeneNames() {
  static const std::vector<std::string> names = {
      "A_pitch", "A_yaw",        "phi_pitch", "phi_yaw",
      "T",       "offset_pitch", "offset_yaw"};
  return names;
}
// Genes of a CPG gait (CpgParameters: coupling, convergence,
// feedback_gain): a genome with any of them runs the gait on coupled
// oscillators (docs/gait.md, "CPG gaits").
inline const std::vector<std::string>& CpgGeneNames() {
  static const std::vector<std::string> names = {
      "cpg_coupling", "cpg_convergence", "cpg_feedback"};
  return names;
}
inline const std::vector<std::string>& BodyGeneNames() {
  static const std::vector<std::string> names = {
      "module_count", "module_mass",   "module_scale",
      "joint_kp",     "joint_max_vel", "sensor_after"};
  return names;
}
// What a known gene can take at all (the gait's and the simulator's own
// limits); nullopt for names it does not know (test functions).
struct GeneRange {
  double min;
  double max;
  bool min_exclusive;         // min itself is not allowed (a mass, a scale)
  const char* why = nullptr;  // why max is the limit, when it is a choice
};
std::optional<GeneRange> GeneRangeOf(const std::string& name);

// Body genes that only take whole numbers.
bool IsIntegerGene(const std::string& name);

// One gene. A gene toggled off (enabled = false) keeps `start`, the user's
// value, in every genome.
struct GeneSpec {
  std::string name;
  double lower = 0.0;
  double upper = 1.0;
  double start = 0.0;
  bool enabled = true;
  bool integer = false;  // values are rounded to whole numbers
};

// A genome's values, one per gene of the spec, in file order.
using Genome = std::vector<double>;

// A bad genome file or spec; what() names the file, line and field.
class GenomeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GenomeSpec {
  std::string robot;  // robot the genes apply to; empty = the first robot
  std::vector<GeneSpec> genes;

  int size() const { return static_cast<int>(genes.size()); }
  // Index of the gene with this name, or -1.
  int Find(const std::string& name) const;
  Genome StartGenome() const;
  // Enabled genes uniform within their limits, disabled genes at start.
  Genome RandomGenome(Random& random) const;
  // The value a gene can take: within [lower, upper], rounded for integer
  // genes, `start` for a disabled gene.
  double Legal(int gene, double value) const;
  // Throws GenomeError when the genome has the wrong size or a value a gene
  // cannot take.
  void Check(const Genome& genome) const;
  // Throws GenomeError on empty/duplicate names, lower > upper, a start
  // outside the limits or a non-finite number.
  void Validate(const std::string& source) const;
};

// The forward gait genome a new user starts from (the genes of
// scenarios/forward_gait.genome.xml): pitch amplitude, phase lag, period
// and offset free; the yaw genes fixed at 0.
GenomeSpec ForwardGaitGenome();

// The built-in genomes of `mrsim-opt --genes`: "sine" frees all seven gait
// parameters (A in [0, 1.5], phi in [-pi, pi], T in [1, 6] s, offsets in
// [-0.3, 0.3]); "cpg" adds cpg_coupling in [0.5, 20] and cpg_convergence
// in [1, 40] (a CPG gait). Throws GenomeError for another name.
GenomeSpec BuiltInGenome(const std::string& name);

// Reads and validates a genome file. Unknown gene names are an error unless
// allow_any_name (test functions use their own names).
GenomeSpec ReadGenomeFile(const std::string& path, bool allow_any_name = false);
GenomeSpec ReadGenomeString(const std::string& xml, const std::string& name,
                            bool allow_any_name = false);
std::string WriteGenomeString(const GenomeSpec& spec);

}  // namespace mrsim
