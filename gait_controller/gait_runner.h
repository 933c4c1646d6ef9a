// Runs a gait controller in closed loop with the physics in one process,
// exactly as mrsim-gait does against mrsim-sim in lockstep: each control
// period the controller advances by the sim time elapsed since the last
// period, its targets are applied, and the physics steps one period. The
// optimiser's episodes and the tests are a few lines on top of this.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "gait_controller/gait_controller.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/robot_state.h"

namespace mrsim {

// The hinge axes of a robot in chain order, for GaitController.
std::vector<Axis> JointAxes(const Physics& physics, int robot);

// Direction of the body from tail to head in the ground plane (rad,
// counter-clockwise from +x): the mean position of the front half of the
// modules minus that of the back half. Robust to the waves of a gait;
// compare headings a whole number of periods apart.
double BodyHeading(const RobotState& state);

// Each module's roll about the body axis given by `heading` (rad): the
// angle of its local z axis from world up, right hand about the axis.
std::vector<double> ModuleRolls(const RobotState& state, double heading);

// Called after every control period, with the physics already stepped and
// the targets that drove that period.
using GaitStepObserver =
    std::function<void(const Physics& physics, const std::vector<double>&)>;

struct GaitRunResult {
  int periods = 0;  // control periods run
  Eigen::Vector3d com_start = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_end = Eigen::Vector3d::Zero();
  double heading_start = 0.0;   // rad, BodyHeading
  double heading_change = 0.0;  // rad, unwrapped over every period
  // rad: mean over the modules of each one's rotation about the body axis
  // (right hand about the tail-to-head direction), unwrapped every period.
  double roll_change = 0.0;
  double energy = 0.0;  // J, sum of |torque * speed| dt over hinges
};

// Runs round(seconds / control_period) periods; control_period must be a
// whole number (>= 1) of physics timesteps. Throws std::invalid_argument on
// a bad robot index or period, and whatever Physics throws.
GaitRunResult RunGait(Physics& physics, int robot, GaitController& controller,
                      double seconds, double control_period = 0.01,
                      const GaitStepObserver& observer = {});

}  // namespace mrsim
