// The MJCF names of every part of a scenario, which the builder gives and the
// physics, viewer and studio look up (docs/physics.md). `robot` is
// RobotName(scenario, i) (Robot::name, or "robot<i>" when empty), indices are
// positions in the scenario's lists. Plain strings: no MJCF text in here.
#pragma once

#include <string>

#include "sim_core/scenario/scenario.h"

namespace mrsim {
namespace mjcf_names {
// Same as mrsim::RobotName (scenario.h).
std::string RobotName(const Scenario& scenario, int robot);
std::string RootJoint(const std::string& robot, int component);  // "r/root"
std::string FrameBody(const std::string& robot, int module, int frame);
std::string Hinge(const std::string& robot, int module);         // "r/m3/hinge"
std::string Servo(const std::string& robot, int module);         // "r/m3/servo"
std::string SensorModuleBody(const std::string& robot, int sm);  // "r/sm2"
// The site of instance k of a sensor kind (sensor_kind.h): "r/sm2/imu"
// (k > 0: "r/sm2/imu1"), "r/sm2/force", "r/sm2/distance1"; its MuJoCo
// sensors "r/sm2/imu/accel" (an empty suffix: the site's own name,
// "r/sm2/force"), and the body of a kPlate instance "r/sm2/force/body".
std::string SensorKindSite(const std::string& robot, int sm, const char* kind,
                           int k);
std::string SensorKindSensor(const std::string& robot, int sm, const char* kind,
                             int k, const char* suffix);
std::string SensorKindBody(const std::string& robot, int sm, const char* kind,
                           int k);
// Shorthands for the viewer and the studio, which draw plates and rays:
// the force plate's body and the k-th distance sensor's site.
std::string PlateBody(const std::string& robot, int sm);
std::string DistanceSite(const std::string& robot, int sm, int k);
std::string Weld(const std::string& robot,
                 const std::string& lock);  // "r/weld/<lock name>"
std::string SceneObject(int index);         // "scene/obj<i>"
// Camera k of scene object `index`, named as a sensor module's:
// "scene/obj2/camera" (k > 0: "scene/obj2/camera1").
std::string SceneObjectCamera(int index, int k);
// The robot name the loose parts' bodies go by: "loose" ("loose/sm0").
std::string LooseRobot();
// Loose joint k's hinge and, when it has one, its servo:
// "loose/j2/hinge", "loose/j2/servo".
std::string LooseHinge(int joint);
std::string LooseServo(int joint);
std::string Terrain();  // "scene/terrain" (hfield or plane)
}  // namespace mjcf_names
}  // namespace mrsim
