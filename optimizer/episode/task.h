// The task suite (docs/tasks.md): named, fixed problems on which gaits and
// optimisers are compared. A task is a scenario (a 12-module pitch-yaw
// chain in a world built for the task) plus the fitness that scores it,
// the episode length it is measured over and the preset to start from.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "gait_controller/gait.h"
#include "optimizer/episode/episode.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

struct Task {
  std::string name;
  std::string world;        // what the world is: docs/tasks.md's table
  std::string description;  // one line: the world and what is scored
  Scenario scenario;        // everything embedded: names no file
  // FitnessSettings::distance_mode: "forward" (+x), or "up" (+z, the pole).
  std::string distance_mode = "forward";
  double duration = 20.0;  // s of sim time the table in tasks.md uses
  // The gait to start from: a preset, or (pole) a preset adapted to the
  // task's start pose.
  Gait gait;
};

// An unknown task name; what() lists the known ones.
class TaskError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// flat, slope, stairs, pegs, pipe, pole, rubble, water.
const std::vector<std::string>& TaskNames();
// "flat, slope, ..." for messages and --help.
std::string TaskNamesText();
// What the task's fitness measures, in metres: "CoM travel along +x" or
// "CoM rise along +z".
std::string TaskFitnessText(const Task& task);
// Builds the task ('_' accepted for '-'). Same name, same task, bit for bit
// (the rubble is seeded). Throws TaskError.
Task MakeTask(const std::string& name);

// The task as an optimisation problem: its scenario, its fitness
// (distance mode, weight 1 on distance) and episode length (`seconds` > 0
// replaces the task's), the given base gait and genome.
Problem TaskProblem(const Task& task, const Gait& gait,
                    const GenomeSpec& genome = {}, double seconds = 0);

// One episode of `gait` on the task (the rows of docs/tasks.md).
EvalResult EvaluateTask(const Task& task, const Gait& gait, double seconds = 0);

// The robot every task uses, and its name in the scenarios.
inline constexpr int kTaskModules = 12;
inline constexpr const char* kTaskRobot = "snake";

}  // namespace mrsim
