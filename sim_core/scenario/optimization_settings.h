// How a design is meant to be optimised, saved with it (<optimization> in
// a scenario file): the algorithm and its budget, the seed, the fitness,
// what the genes drive and which genes. `mrsim-opt FILE` and the studio's
// Optimise section start from these; a flag given to mrsim-opt overrides
// the file's value (docs/optimizer.md, "The setup in the design file").
//
// Plain data: the scenario library is below the optimizer, so the words
// (algorithm, distance, controller, gene set) and the genome's text are
// kept as written and checked by the optimizer when it uses them, naming
// the file's line and field (optimizer/process/opt_file_setup.h).
#pragma once

#include <cstddef>
#include <string>

#include "sim_core/scenario/reality_gap_limits.h"

namespace mrsim {

// Bounds on the text an <optimization> element carries (docs/scenario.md,
// "Limits").
inline constexpr size_t kMaxOptimizationWordBytes = 64;  // names and words
// A genome file's text (docs/optimizer.md): a gene is a line of well under
// 200 bytes, so this holds far more genes than any body and gait have.
inline constexpr size_t kMaxGenomeTextBytes = size_t{64} << 10;
// Algorithm settings "flag=value ..." (every algorithm's, several times).
inline constexpr size_t kMaxAlgorithmSettingsBytes = 4096;
inline constexpr size_t kMaxPathBytes = 4096;  // a base gait's file

// Defaults are mrsim-opt's, so a field left out of a file means what
// leaving out the flag means (a test holds them equal).
struct OptimizationSettings {
  std::string algorithm = "ga";  // a name of mrsim-opt --algorithm
  int generations = 20;
  int population = 16;
  int seed = 1;
  double episode = 20;  // s of simulated time per episode
  // mrsim-opt --controller: gait, cpg, lua (the <run> element's script),
  // lua:FILE (beside the design), mlp:H...
  std::string controller = "gait";
  std::string genes;      // a built-in gene set (--genes): sine | cpg
  std::string genome;     // a genome file's text (--genome), e.g. edited genes
  std::string task;       // a task of the suite (--task) instead of this world
  std::string base_gait;  // --gait: a preset or a gait file; "": forward
  std::string distance = "forward";  // --distance: forward | net | up
  double w_distance = 1;
  double w_speed = 0;
  double w_energy = 0;
  double w_drift = 0;
  double w_fall = 0;
  int robust = 0;                    // --robust K
  std::string robust_mode = "mean";  // --robust-mode: mean | worst
  bool allow_overlap = false;        // --allow-overlap
  // The reality gap of the K robust episodes (RealityGap, docs/physics.md
  // "The reality gap"); defaults are RealityGap::Typical(), the limits its
  // Validate's (reality_gap_limits.h). Units as RealityGap's fields.
  double gap_sensor_noise = kGapTypicalSensorNoise;
  double gap_sensor_bias = kGapTypicalSensorBias;
  double gap_joint_noise = kGapTypicalJointNoise;  // rad
  double gap_motor_noise = kGapTypicalMotorNoise;  // rad/s
  double gap_latency = kGapTypicalLatency;         // s
  double gap_backlash = kGapTypicalBacklash;       // rad
  double gap_max_accel = kGapTypicalMaxAccel;      // rad/s^2
  double gap_friction_range = kGapTypicalFrictionRange;
  double gap_mass_range = kGapTypicalMassRange;
  double gap_gain_range = kGapTypicalGainRange;
  double gap_terrain_range = kGapTypicalTerrainRange;
  // The chosen algorithm's own settings as "flag=value" words separated by
  // spaces ("cmaes-sigma=0.2"), each a flag of mrsim-opt.
  std::string algorithm_settings;
};

// Field by field, as the schema lists them (defined with the scenario's).
bool operator==(const OptimizationSettings& a, const OptimizationSettings& b);
inline bool operator!=(const OptimizationSettings& a,
                       const OptimizationSettings& b) {
  return !(a == b);
}

}  // namespace mrsim
