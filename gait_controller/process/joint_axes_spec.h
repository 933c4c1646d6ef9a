// Which hinge of the robot is pitch and which is yaw, for mrsim-gait: the
// state message does not say, so it comes from the scenario file or a flag.
#pragma once

#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// "pitch", "yaw", "pitch-yaw", "yaw-pitch" (alternating, any length) or
// one letter per joint ("PYPYP"). Throws std::invalid_argument on anything
// else.
class JointAxesSpec {
 public:
  explicit JointAxesSpec(const std::string& spec);
  // The axes of a chain of joint_count hinges. Throws std::invalid_argument
  // when an explicit list has another length.
  std::vector<Axis> Expand(int joint_count) const;

 private:
  std::string pattern_;
  std::vector<Axis> explicit_;
};

// The hinge axes of the named robot in a scenario file, in chain order
// (modules whose joint is a Hinge). Throws std::invalid_argument naming the
// robots the file has when there is no such robot, and ScenarioError on a
// bad file.
std::vector<Axis> ScenarioJointAxes(const std::string& scenario_path,
                                    const std::string& robot);

}  // namespace mrsim
