// Loads a scenario, runs a preset gait on its first robot and prints how far
// the robot's centre of mass travelled. Usage: distance SCENARIO [GAIT]
// [SECONDS]
#include <iostream>
#include <string>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: distance SCENARIO [GAIT] [SECONDS]\n";
    return 2;
  }
  try {
    const std::string gait_name = argc > 2 ? argv[2] : "forward";
    const double seconds = argc > 3 ? std::stod(argv[3]) : 10.0;

    mrsim::Physics physics(mrsim::ReadScenarioFile(argv[1]));
    mrsim::GaitController controller(mrsim::JointAxes(physics, 0));
    const auto gait = mrsim::FindGaitPreset(gait_name);
    if (!gait) {
      std::cerr << "unknown gait " << gait_name << "\n";
      return 2;
    }
    controller.SetGait(*gait);

    const mrsim::GaitRunResult run =
        mrsim::RunGait(physics, 0, controller, seconds);
    const Eigen::Vector3d moved = run.com_end - run.com_start;
    std::cout << physics.robot_name(0) << " moved " << moved.norm() << " m in "
              << seconds << " s (dx " << moved.x() << ", dy " << moved.y()
              << ")\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "distance: " << e.what() << "\n";
    return 1;
  }
}
