// The MJCF names of every part of a scenario, which the builder gives and the
// physics, viewer and studio look up (docs/physics.md). `robot` is
// RobotName(scenario, i) (Robot::name, or "robot<i>" when empty), indices are
// positions in the scenario's lists. Plain strings: no MJCF text in here.
#pragma once

#include <string>

#include "sim_core/scenario.h"

namespace mrsim {
namespace mjcf_names {
// Same as mrsim::RobotName (scenario.h).
std::string RobotName(const Scenario& scenario, int robot);
std::string RootJoint(const std::string& robot, int component);  // "r/root"
std::string FrameBody(const std::string& robot, int module, int frame);
std::string Hinge(const std::string& robot, int module);         // "r/m3/hinge"
std::string Servo(const std::string& robot, int module);         // "r/m3/servo"
std::string SensorModuleBody(const std::string& robot, int sm);  // "r/sm2"
std::string PlateBody(const std::string& robot, int sm);    // "r/sm2/plate"
std::string ForceSite(const std::string& robot, int sm);    // ".../plate_site"
std::string ForceSensor(const std::string& robot, int sm);  // "r/sm2/force"
std::string DistanceSite(const std::string& robot, int sm,
                         int k);  // "r/sm2/d0"
std::string Weld(const std::string& robot,
                 const std::string& lock);  // "r/weld/<lock name>"
std::string SceneObject(int index);         // "scene/obj<i>"
std::string Terrain();                      // "scene/terrain" (hfield or plane)
}  // namespace mjcf_names
}  // namespace mrsim
