// What one evaluation of a genome gives back: the fitness (higher is better)
// and the episode metrics it was made of.
#pragma once

#include <string>

namespace mrsim {

struct EvalResult {
  double fitness = 0.0;
  double distance = 0.0;  // m, CoM travel (see FitnessSettings::mode)
  double speed = 0.0;     // m/s, distance / duration
  double energy = 0.0;    // J, sum of |torque * speed| dt over the hinges
  double drift = 0.0;     // m, |lateral CoM displacement|
  double fell = 0.0;      // fraction of the episode spent upside down
  bool failed = false;    // the simulation became unstable
  // Why it failed, when a controller said (a Lua script's error message);
  // "" otherwise. Written in evaluations.csv's error column.
  std::string error;
};

}  // namespace mrsim
