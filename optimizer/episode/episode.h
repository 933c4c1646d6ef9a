// One evaluation of a genome: a headless episode at full speed through the
// sim_core and gait libraries (no LCM), scored by the fitness settings.
// Deterministic: the same problem and genome give the same result bit for
// bit, in any thread or process of the same build.
#pragma once

#include <functional>
#include <string>

#include "common/enum_table.h"
#include "gait_controller/gait.h"
#include "optimizer/episode/controller_spec.h"
#include "optimizer/search/batch_evaluator.h"
#include "optimizer/search/eval_result.h"
#include "optimizer/search/genome.h"
#include "sim_core/physics/reality_gap.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// "forward": CoM displacement along +x (the chain's head direction, see
// chain_builder.h); "net": horizontal CoM displacement in any direction;
// "up": CoM rise along +z (climbing, the pole task).
enum class DistanceMode { kForward, kNet, kUp };
const EnumTable<DistanceMode>& DistanceModes();
inline const char* ToString(DistanceMode mode) {
  return DistanceModes().Name(mode);
}
// Throws std::invalid_argument naming `field` and every valid word.
inline DistanceMode ParseDistanceMode(
    const std::string& text,
    const std::string& field = "fitness distance mode") {
  return DistanceModes().Parse(text, field);
}

// Fitness = distance * w_distance + speed * w_speed - energy * w_energy
//           - drift * w_drift - fell * w_fall            (higher is better)
struct FitnessSettings {
  DistanceMode distance_mode = DistanceMode::kForward;
  double w_distance = 1.0;
  double w_speed = 0.0;
  double w_energy = 0.0;
  double w_drift = 0.0;
  double w_fall = 0.0;
};

// Fitness of an episode whose simulation became unstable.
inline constexpr double kFailedFitness = -1e6;

// Robust fitness (`mrsim-opt --robust K`): the episode runs K times, the
// k-th in the world of gap.ForEpisode(k) (PerturbScenario, then the
// per-step imperfections of Physics::SetRealityGap), and the fitness is the
// mean or the worst of the K. Every genome meets the same K worlds, so
// their fitnesses compare; gap.seed comes from the run's seed and travels
// in the problem payload to farm workers (docs/optimizer.md).
struct RobustSettings {
  static constexpr int kMaxEpisodes = 1000;
  int episodes = 0;           // K; 0: the nominal episode only
  std::string mode = "mean";  // "mean" or "worst"
  RealityGap gap = RealityGap::Typical();

  // Throws std::invalid_argument naming the setting.
  void Validate() const;
};

struct EpisodeSettings {
  double duration = 20.0;        // s of simulated time
  double control_period = 0.01;  // s, a whole number of physics steps
  FitnessSettings fitness;
  // The gait whose seven parameters the gait genes replace (genes not in
  // the genome keep this gait's values); its kind selects the motion.
  Gait base_gait;
  RobustSettings robust;
  // A body the body genes grow into itself or the scene runs anyway
  // (mrsim-opt --allow-overlap, the design's allowOverlap); otherwise it
  // is a failed individual whose EvalResult::error names the parts. In
  // the payload, so a farm's workers decide as one process does.
  bool allow_overlap = false;

  // Throws std::invalid_argument naming the setting.
  void Validate() const;
};

// Everything an evaluation needs; a worker receives exactly this.
struct Problem {
  Scenario scenario;  // assets embedded (see problem_codec.h)
  GenomeSpec genome;
  EpisodeSettings episode;
  // What drives the robot (the gait unless --controller says otherwise);
  // the gait genes and base gait mean something only for the gait.
  ControllerSpec controller;
};

// The gait an individual runs: the base gait with the gait genes applied.
Gait GaitOfGenome(const Problem& problem, const Genome& genome);

class EpisodePhysicsPool;

// Runs the episode. An unstable simulation, gait values the controller
// refuses, a controller that fails (a Lua error), a body the validator
// refuses or, built from module_count, module_scale or sensor_after genes
// without episode.allow_overlap, one whose parts overlap at the start
// (overlap_check.h) give failed = true and kFailedFitness, never an
// exception; EvalResult::error then says why in one line ("overlap at the
// start: robot 'snake' module 0 front frame / scene object 'ball'", the
// deepest pair), the same on every worker; a genome of the wrong size or a
// robot not in the scenario throws. `stop` (optional) is polled every ten
// control periods: when it returns true the episode is abandoned with
// EvaluationInterrupted, so Ctrl-C does not wait for a long episode.
// `pool` (optional, see episode_physics_pool.h): where the simulation is
// taken from and given back to, so the next episode of the same body
// resets it instead of building one (bit for bit the same result); without
// one the episode builds its own.
EvalResult RunEpisode(const Problem& problem, const Genome& genome,
                      const std::function<bool()>& stop = {},
                      EpisodePhysicsPool* pool = nullptr);

// Builds the simulation of the problem's start genome into `pool`, so that
// a first episode of that body does not pay the build (a worker does it
// while it waits for its first job). Never throws: a problem that cannot
// be built fails in its episodes as before.
void PrepareEpisode(const Problem& problem, EpisodePhysicsPool* pool);

}  // namespace mrsim
