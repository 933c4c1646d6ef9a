#include "tests/physics/test_scenes.h"

namespace mrsim::testing {

Robot SensorModuleRobot(const std::string& name,
                        const Eigen::Vector3d& position, double mass,
                        const Eigen::Vector3d& size) {
  Robot robot;
  robot.name = name;
  SensorModule sm;
  sm.guid = name + "/s0";
  sm.position = position;
  sm.mass = mass;
  sm.size = size;
  robot.sensor_modules.push_back(sm);
  return robot;
}

Robot CantileverModule(const std::string& name, const Eigen::Vector3d& hinge,
                       Axis axis, double kp, double max_vel, double limit) {
  Robot robot;
  robot.name = name;
  Module m;
  m.position = hinge;
  m.axis = axis;
  for (int f = 0; f < 2; ++f) {
    Frame& frame = m.frames[f];
    frame.guid = name + "/f" + std::to_string(f);
    frame.scale = Eigen::Vector3d(0.05, 0.05, 0.05);
    frame.position = hinge + Eigen::Vector3d(f == 0 ? 0.025 : -0.025, 0, 0);
    frame.mass = 0.05;
    frame.is_static = f == 0;
  }
  m.joint.guid = name + "/joint";
  m.joint.left_frame_guid = m.frames[0].guid;
  m.joint.right_frame_guid = m.frames[1].guid;
  m.joint.kp = kp;
  m.joint.max_vel = max_vel;
  m.joint.lower_range_limit = -limit;
  m.joint.upper_range_limit = limit;
  robot.modules.push_back(m);
  return robot;
}

Scenario FlatScenario() {
  Scenario s;
  s.contact_frictions.push_back({"plastic", "ground", 0.0, 0.6, 2e9});
  s.contact_frictions.push_back({"plastic", "plastic", 0.0, 0.4, 2e9});
  return s;
}

int CollidingRobotGeoms(const mjModel* m) {
  int n = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    n += m->geom_bodyid[g] != 0 &&
         (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0);
  }
  return n;
}

}  // namespace mrsim::testing
