// How one gait run is measured, for everything that reports what a gait
// does: bench_gait's table, the gait atlas (docs/gait_atlas.csv) and its
// tests. They all measure through MeasureGait, so a number in one of them
// means the same in the others.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "gait_controller/gait.h"
#include "sim_core/scenario/chain_builder.h"

namespace mrsim {

// The robot, the world and the clock of one run: a MakeChain robot on flat
// ground (MuJoCo's default friction 1), or a world of its own, the gait set
// with SetGait and then the motion, if any, run in closed loop by RunGait.
struct GaitTrial {
  ChainOptions chain;           // 11 modules, all-pitch by default
  bool passive_wheels = false;  // on every module (docs/physics.md)
  // Set: run in this world instead; its robot 0 is measured and `chain`
  // only gives the body length (the task suite's worlds, docs/tasks.md).
  std::optional<Scenario> world;
  double seconds = 20.0;         // the whole run
  double settle = 4.0;           // s of ramp-in before the speed is timed
  double control_period = 0.01;  // s, as mrsim-gait at 100 Hz
  std::optional<Motion> motion;  // unset: the gait's own kind, forward
  double strength = 1.0;         // of the motion
};

// The chain bench_gait runs a gait on: pitch-yaw when the gait or the
// motion moves yaw joints, all-pitch otherwise.
ChainPattern ChainFor(const Gait& gait, std::optional<Motion> motion = {});

// "pitch", "yaw" or "pitch-yaw".
std::string ChainPatternName(ChainPattern pattern);

// What one run did. Speeds are in body lengths (two frames per module)
// per second over the timed part (after `settle`); heading and roll over
// the whole run.
struct GaitOutcome {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // CoM, timed part
  double speed = 0.0;        // bl/s, horizontal displacement
  double drift = 0.0;        // bl/s across the body (left +) at `settle`
  double rise = 0.0;         // bl/s, vertical displacement (a climb)
  double heading_deg = 0.0;  // BodyHeading change, unwrapped
  double roll_deg = 0.0;     // mean module roll about the body axis
  double body_length = 0.0;  // m
};

// Runs `gait` as `trial` says. Deterministic: the same gait and trial give
// the same outcome bit for bit. Throws std::invalid_argument when settle
// is not in [0, seconds), and whatever the physics or RunGait throw.
GaitOutcome MeasureGait(const Gait& gait, const GaitTrial& trial);

}  // namespace mrsim
