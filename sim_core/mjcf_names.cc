#include "sim_core/mjcf_names.h"

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
std::string PlateBody(const std::string& robot, int sm) {
  return SensorModuleBody(robot, sm) + "/plate";
}
std::string ForceSite(const std::string& robot, int sm) {
  return SensorModuleBody(robot, sm) + "/plate_site";
}
std::string ForceSensor(const std::string& robot, int sm) {
  return SensorModuleBody(robot, sm) + "/force";
}
std::string DistanceSite(const std::string& robot, int sm, int k) {
  return SensorModuleBody(robot, sm) + "/d" + std::to_string(k);
}
std::string Weld(const std::string& robot, const std::string& lock) {
  return robot + "/weld/" + lock;
}
std::string SceneObject(int index) {
  return "scene/obj" + std::to_string(index);
}
std::string Terrain() { return "scene/terrain"; }
}  // namespace mjcf_names

}  // namespace mrsim
