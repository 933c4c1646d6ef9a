#include "studio/design/selection_name.h"

#include <sstream>

#include "studio/design/design.h"

namespace mrsim::studio {
namespace {

// "module 3" -> index 3 of `kind` ("module" or "sensor_module"), -1 when
// `words` is not that.
int PlaceOf(const std::string& words, const std::string& kind) {
  std::istringstream in(words);
  std::string word, rest;
  int n = -1;
  if (!(in >> word >> n) || word != kind || n < 0 || (in >> rest)) return -1;
  return n;
}

}  // namespace

Selection SelectionNamed(const Scenario& s, const std::string& name) {
  for (size_t r = 0; r < s.robots.size(); ++r) {
    if (s.robots[r].name == name) {
      return {SelectionKind::kRobot, static_cast<int>(r), 0};
    }
  }
  for (size_t i = 0; i < s.scene_objects.size(); ++i) {
    if (s.scene_objects[i].guid == name) {
      return {SelectionKind::kSceneObject, 0, static_cast<int>(i)};
    }
  }
  if (name == "none") return {};
  if (name == "terrain") return {SelectionKind::kScene, 0, 0};
  if (name == "settings") return {SelectionKind::kSettings, 0, 0};
  // A part: "[ROBOT ]module N" or "[ROBOT ]sensor_module N".
  int robot = 0;
  std::string part = name;
  for (size_t r = 0; r < s.robots.size(); ++r) {
    const std::string prefix = s.robots[r].name + " ";
    if (name.compare(0, prefix.size(), prefix) == 0) {
      robot = static_cast<int>(r);
      part = name.substr(prefix.size());
    }
  }
  if (!s.robots.empty()) {
    const Robot& r = s.robots[robot];
    const int module = PlaceOf(part, "module");
    if (module >= 0 && module < static_cast<int>(r.modules.size())) {
      return {SelectionKind::kModule, robot, module};
    }
    const int sensor = PlaceOf(part, "sensor_module");
    if (sensor >= 0 && sensor < static_cast<int>(r.sensor_modules.size())) {
      return {SelectionKind::kSensorModule, robot, sensor};
    }
    const int lock = PlaceOf(part, "lock");
    if (lock >= 0 && lock < static_cast<int>(r.locks.size())) {
      return {SelectionKind::kLock, robot, lock};
    }
  }
  const int loose_frame = PlaceOf(name, "loose_frame");
  if (loose_frame >= 0 &&
      loose_frame < static_cast<int>(s.loose_frames.size())) {
    return {SelectionKind::kLooseFrame, 0, loose_frame};
  }
  const int loose_joint = PlaceOf(name, "loose_joint");
  if (loose_joint >= 0 &&
      loose_joint < static_cast<int>(s.loose_joints.size())) {
    return {SelectionKind::kLooseJoint, 0, loose_joint};
  }
  const int loose_sm = PlaceOf(name, "loose_sensor_module");
  if (loose_sm >= 0 &&
      loose_sm < static_cast<int>(s.loose_sensor_modules.size())) {
    return {SelectionKind::kLooseSensorModule, 0, loose_sm};
  }
  std::string robots, objects;
  for (const Robot& r : s.robots)
    robots += (robots.empty() ? "" : ", ") + r.name;
  for (const SceneObject& o : s.scene_objects) {
    objects += (objects.empty() ? "" : ", ") + o.guid;
  }
  throw DesignError("nothing named '" + name + "' to select (robots: " +
                    (robots.empty() ? "none" : robots) +
                    "; objects: " + (objects.empty() ? "none" : objects) +
                    "; or [ROBOT ]module N, [ROBOT ]sensor_module N, "
                    "[ROBOT ]lock N, loose_frame N, loose_joint N, "
                    "loose_sensor_module N, terrain, settings, none)");
}

}  // namespace mrsim::studio
