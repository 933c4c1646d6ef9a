// MuJoCo's process-wide error and warning callbacks, set so that MuJoCo
// never prints, never writes MUJOCO_LOG.TXT and never ends the process.
#pragma once

#include <string>

#include "sim_core/mujoco/physics_error.h"

namespace mrsim {

// Thrown from MuJoCo's error callback (mju_error), through MuJoCo's own
// frames, where MuJoCo's default would print, log and exit. A PhysicsError,
// so whoever handles an unstable step handles this too; the mjData it came
// from must be reset (Physics::Reset) before it steps again.
class MujocoError : public PhysicsError {
 public:
  using PhysicsError::PhysicsError;
};

// Installs the callbacks once per process; later calls do nothing, and
// callbacks the application set before the first call are kept. Errors
// throw MujocoError. Warnings (e.g. "Nan, Inf or huge value in QACC") are
// counted and the last one kept; Physics turns the unstable-state ones into
// PhysicsError through mjData's warning counters. Thread-safe.
void InstallMujocoHandlers();

// Warnings MuJoCo reported through the callback in this process so far.
long MujocoWarningCount();
// The text of the last one ("" if none).
std::string LastMujocoWarning();

}  // namespace mrsim
