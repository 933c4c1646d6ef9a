#include "optimizer/episode/body_genes.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace mrsim {

int GenomeRobotIndex(const Scenario& scenario, const GenomeSpec& spec) {
  if (scenario.robots.empty()) {
    throw GenomeError("the scenario has no robot to optimise");
  }
  if (spec.robot.empty()) return 0;
  for (size_t i = 0; i < scenario.robots.size(); ++i) {
    if (scenario.robots[i].name == spec.robot) return static_cast<int>(i);
  }
  throw GenomeError("genome: robot '" + spec.robot +
                    "' is not in the scenario");
}

ChainOptions ChainOptionsOf(const Robot& robot) {
  if (robot.modules.empty()) {
    throw GenomeError("robot '" + robot.name + "' has no modules to rebuild");
  }
  const Module& m0 = robot.modules.front();
  ChainOptions o;
  o.name = robot.name;
  o.modules = static_cast<int>(robot.modules.size());
  bool pitch = true, yaw = true;
  for (const Module& m : robot.modules) {
    pitch = pitch && m.axis == Axis::kPitch;
    yaw = yaw && m.axis == Axis::kYaw;
  }
  o.pattern = pitch ? ChainPattern::kPitch
                    : (yaw ? ChainPattern::kYaw : ChainPattern::kPitchYaw);
  o.module_mass = m0.frames[0].mass + m0.frames[1].mass;
  o.frame_size = m0.frames[0].scale;
  o.kp = m0.joint.kp;
  o.max_vel = m0.joint.max_vel;
  o.joint_limit = std::max(std::abs(m0.joint.lower_range_limit),
                           std::abs(m0.joint.upper_range_limit));
  o.material = m0.frames[0].material_name;
  o.sensor_after.clear();
  for (const SensorModule& sm : robot.sensor_modules) {
    o.force_sensors = o.force_sensors || sm.force_sensor.has_value();
    o.front_distance_sensor =
        o.front_distance_sensor ||
        (sm.left_mod_nr == -1 && !sm.distance_sensors.empty());
    o.sensor_after.push_back(sm.left_mod_nr);
  }
  const double lift = o.force_sensors ? ForceSensor().size.z() : 0.0;
  o.origin = Eigen::Vector3d(m0.position.x(), m0.position.y(),
                             m0.position.z() - o.frame_size.z() / 2 - lift);
  return o;
}

namespace {

// Scales every length of `robot` by `factor` about the point at ground
// height (Scene::position.z) under module 0's hinge, so it still stands
// there whatever its frames' shapes.
void ScaleRobot(Robot* robot, double ground_z, double factor) {
  if (robot->modules.empty()) {
    throw GenomeError("robot '" + robot->name + "' has no modules to scale");
  }
  const Eigen::Vector3d origin(robot->modules[0].position.x(),
                               robot->modules[0].position.y(), ground_z);
  Scenario one;
  one.robots.push_back(*robot);
  ScaleLengths(&one, factor);
  Robot& r = one.robots.front();
  const Eigen::Vector3d shift = origin - factor * origin;
  for (Module& m : r.modules) {
    m.position += shift;
    for (Frame& f : m.frames) f.position += shift;
  }
  for (SensorModule& sm : r.sensor_modules) {
    sm.position += shift;
    sm.force_lock_position += shift;
    sm.distance_lock_position += shift;
    if (sm.force_sensor) sm.force_sensor->position += shift;
    for (DistanceSensor& d : sm.distance_sensors) d.position += shift;
  }
  *robot = r;
}

}  // namespace

bool GenomeBuildsTheBody(const GenomeSpec& spec) {
  for (const char* name : {"module_count", "module_scale", "sensor_after"}) {
    if (spec.Find(name) >= 0) return true;
  }
  return false;
}

Scenario ApplyBodyGenes(const Scenario& scenario, const GenomeSpec& spec,
                        const Genome& genome) {
  Scenario s = scenario;
  const int r = GenomeRobotIndex(s, spec);
  Robot& robot = s.robots[r];
  auto gene = [&](const char* name, double* value) {
    const int i = spec.Find(name);
    if (i < 0) return false;
    *value = genome[i];
    return true;
  };
  double count = 0, scale = 1, sensor = 0;
  const bool rebuild_count = gene("module_count", &count);
  const bool rebuild_scale = gene("module_scale", &scale);
  const bool rebuild_sensor = gene("sensor_after", &sensor);
  if (rebuild_scale && !rebuild_count && !rebuild_sensor) {
    // Scaling needs no rebuild: every part (mesh frames and hand-placed
    // sensors too) grows about the ground point under module 0's hinge.
    ScaleRobot(&robot, s.scene.position.z(), scale);
  } else if (rebuild_count || rebuild_scale || rebuild_sensor) {
    ChainOptions o = ChainOptionsOf(robot);
    if (rebuild_count) o.modules = static_cast<int>(std::lround(count));
    if (rebuild_scale) {
      // Keep the ground point: origin.z is the ground, not a centre.
      o.frame_size *= scale;
    }
    if (rebuild_sensor) {
      // The first sensor module moves; the others keep their places.
      const int after = static_cast<int>(std::lround(sensor));
      if (o.sensor_after.empty()) {
        o.sensor_after.push_back(after);
      } else {
        o.sensor_after.front() = after;
      }
    }
    std::vector<int> kept;
    std::set<int> seen;
    for (int after : o.sensor_after) {
      const int a = std::clamp(after, -1, o.modules - 1);
      if (seen.insert(a).second) kept.push_back(a);
    }
    o.sensor_after = kept;
    // A forward ray looks out only from a sensor module in front of module
    // 0: behind a module it would read 0, so the rebuilt robot has none.
    if (std::find(kept.begin(), kept.end(), -1) == kept.end()) {
      o.front_distance_sensor = false;
    }
    robot = MakeChain(o);
  }
  double value = 0;
  if (gene("joint_kp", &value)) {
    for (Module& m : robot.modules) m.joint.kp = value;
  }
  if (gene("joint_max_vel", &value)) {
    for (Module& m : robot.modules) m.joint.max_vel = value;
  }
  if (gene("module_mass", &value)) {
    for (Module& m : robot.modules) {
      m.frames[0].mass = value / 2;
      m.frames[1].mass = value / 2;
    }
  }
  return s;
}

}  // namespace mrsim
