// The controllers an episode can run besides the built-in gait (which
// RunGait drives, unchanged): each control period it is given the sim
// time and the robot's state and answers one joint target per hinge.
// MakeEpisodeController is the seam a new controller kind plugs into.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gait_controller/gait_runner.h"
#include "optimizer/search/genome.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

struct Problem;

// A controller that cannot go on (a Lua error, say): the episode fails,
// its message kept in the evaluation (evaluations.csv's error column).
class ControllerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class EpisodeController {
 public:
  virtual ~EpisodeController() = default;
  // The targets (rad, one per joint) for the period starting at sim time
  // t, the robot being in `state`. Throws ControllerError.
  virtual const std::vector<double>& Targets(double t,
                                             const RobotState& state) = 0;
};

// The problem's controller for `genome` on a robot with these hinge axes;
// nullptr for the gait (RunEpisode runs it through RunGait). Throws
// ControllerError when it cannot be made (a script that no longer loads).
std::unique_ptr<EpisodeController> MakeEpisodeController(
    const Problem& problem, const Genome& genome,
    const std::vector<Axis>& axes);

// What the episode's fitness is made of.
struct ControllerRunResult {
  Eigen::Vector3d com_start = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_end = Eigen::Vector3d::Zero();
  double energy = 0.0;  // J, sum of |torque * speed| dt over hinges
};

// RunGait's loop for any EpisodeController: round(seconds /
// control_period) periods, the controller asked at the start of each with
// the sim time and the state read after the last, as mrsim-lua answers
// mrsim-sim in lockstep. Throws std::invalid_argument for a period that
// is not a whole number of steps or targets of the wrong count, and what
// Physics and the controller throw.
ControllerRunResult RunController(Physics& physics, int robot,
                                  EpisodeController& controller, double seconds,
                                  double control_period,
                                  const GaitStepObserver& observer = {});

}  // namespace mrsim
