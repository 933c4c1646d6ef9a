#include "sim_core/mjcf/mjcf_names.h"

namespace mrsim {

namespace mjcf_names {
std::string RobotName(const Scenario& scenario, int robot) {
  return mrsim::RobotName(scenario, robot);
}
std::string RootJoint(const std::string& robot, int component) {
  return robot + "/root" + (component == 0 ? "" : std::to_string(component));
}
std::string FrameBody(const std::string& robot, int module, int frame) {
  return robot + "/m" + std::to_string(module) + "/f" + std::to_string(frame);
}
std::string Hinge(const std::string& robot, int module) {
  return robot + "/m" + std::to_string(module) + "/hinge";
}
std::string Servo(const std::string& robot, int module) {
  return robot + "/m" + std::to_string(module) + "/servo";
}
std::string SensorModuleBody(const std::string& robot, int sm) {
  return robot + "/sm" + std::to_string(sm);
}
std::string SensorKindSite(const std::string& robot, int sm, const char* kind,
                           int k) {
  return SensorModuleBody(robot, sm) + "/" + kind +
         (k == 0 ? "" : std::to_string(k));
}
std::string SensorKindSensor(const std::string& robot, int sm, const char* kind,
                             int k, const char* suffix) {
  if (suffix[0] == '\0') return SensorKindSite(robot, sm, kind, k);
  return SensorKindSite(robot, sm, kind, k) + "/" + suffix;
}
std::string SensorKindBody(const std::string& robot, int sm, const char* kind,
                           int k) {
  return SensorKindSite(robot, sm, kind, k) + "/body";
}
std::string PlateBody(const std::string& robot, int sm) {
  return SensorKindBody(robot, sm, "force", 0);
}
std::string DistanceSite(const std::string& robot, int sm, int k) {
  return SensorKindSite(robot, sm, "distance", k);
}
std::string Weld(const std::string& robot, const std::string& lock) {
  return robot + "/weld/" + lock;
}
std::string SceneObject(int index) {
  return std::string(kSceneOwnerName) + "/obj" + std::to_string(index);
}
std::string SceneObjectCamera(int index, int k) {
  return SceneObject(index) + "/camera" + (k == 0 ? "" : std::to_string(k));
}
std::string LooseRobot() { return kLooseOwnerName; }
std::string LooseHinge(int joint) {
  return LooseRobot() + "/j" + std::to_string(joint) + "/hinge";
}
std::string LooseServo(int joint) {
  return LooseRobot() + "/j" + std::to_string(joint) + "/servo";
}
std::string Terrain() { return "scene/terrain"; }
}  // namespace mjcf_names

}  // namespace mrsim
