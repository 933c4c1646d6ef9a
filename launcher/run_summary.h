// What a run did, from its start (the scenario) and its end (a checkpoint):
// how far each robot's centre of mass and each movable scene object went.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"

namespace mrsim {

struct Displacement {
  // The robot's name; an object's as the user called it ("ball"), or
  // "object <i>" when it has none (SceneObjectLabel).
  std::string name;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double distance() const { return (end - start).norm(); }
};

struct RunSummary {
  double sim_time = 0.0;  // s, at the end
  std::vector<Displacement> robots;
  std::vector<Displacement> objects;  // movable scene objects only
};

// `start` and `end` must be built from the same scenario; otherwise throws
// std::invalid_argument saying so.
RunSummary SummarizeRun(const Physics& start, const Physics& end);

// One line: "20.0 s: case_study moved 0.540 m (dx +0.537, dy +0.000);
// ball displaced 0.317 m (dx +0.317, dy +0.000)".
std::string FormatRunSummary(const RunSummary& summary);

}  // namespace mrsim
