#include "sim_core/scenario/chain_builder.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "sim_core/scenario/scenario_schema.h"

namespace mrsim {
namespace {

// One element of the chain from front to back.
struct Part {
  bool is_sensor = false;
  int index = 0;      // module number or sensor module number
  double length = 0;  // along x
  double center = 0;  // x of its centre, before shifting
};

}  // namespace

std::vector<int> SensorsAfter(SensorPlacement placement, int modules) {
  std::vector<int> after;
  if (placement == SensorPlacement::kNone) return after;
  const bool all = placement == SensorPlacement::kAll;
  for (int i = all ? -1 : 0; i < (all ? modules : modules - 1); ++i) {
    after.push_back(i);
  }
  return after;
}

Scenario MakeChainScenario(const ChainScenarioOptions& options) {
  Scenario s;
  s.robots.push_back(MakeChain(options.chain));
  s.scene.guid = "scene";
  s.scene.material_name = options.ground_material;
  if (options.friction >= 0) {
    ContactFriction pair;
    pair.material1 = options.chain.material;
    pair.material2 = options.ground_material;
    pair.friction = options.friction;
    s.contact_frictions.push_back(pair);
  }
  return s;
}

Joint MakeLock(const std::string& guid, const std::string& left,
               const std::string& right) {
  Joint lock;
  lock.guid = guid;
  lock.left_frame_guid = left;
  lock.right_frame_guid = right;
  lock.type = JointType::kLock;
  lock.lower_range_limit = 0.0;
  lock.upper_range_limit = 0.0;
  return lock;
}

Robot MakeChain(const ChainOptions& options) {
  if (options.modules < 1) {
    throw std::invalid_argument("MakeChain: modules must be at least 1, got " +
                                std::to_string(options.modules));
  }
  if (options.modules > kMaxModules) {
    // A billion modules would be built before anything refused them.
    throw std::invalid_argument("MakeChain: modules must be at most " +
                                std::to_string(kMaxModules) + ", got " +
                                std::to_string(options.modules) + " (" +
                                kMaxModulesWhy + ")");
  }
  if (!(options.frame_size.minCoeff() > 0)) {
    throw std::invalid_argument("MakeChain: frame_size must be positive");
  }
  if (!(options.module_mass > 0)) {
    throw std::invalid_argument("MakeChain: module_mass must be positive");
  }
  if (!(options.joint_limit >= 0)) {
    throw std::invalid_argument("MakeChain: joint_limit must be >= 0");
  }
  std::set<int> sensors;
  for (int after : options.sensor_after) {
    if (after < -1 || after >= options.modules) {
      throw std::invalid_argument("MakeChain: sensor module after module " +
                                  std::to_string(after) + " is outside [-1, " +
                                  std::to_string(options.modules - 1) + "]");
    }
    if (!sensors.insert(after).second) {
      throw std::invalid_argument(
          "MakeChain: two sensor modules after module " +
          std::to_string(after));
    }
  }

  // The ray starts on the front face: behind a module it would start
  // inside that module and read about 0 (the validator refuses it too).
  if (options.front_distance_sensor && !sensors.count(-1)) {
    throw std::invalid_argument(
        sensors.empty()
            ? "MakeChain: a front distance sensor needs a sensor module to "
              "carry it, in front of module 0 (sensor after -1; mrsim-scenario "
              "new --sensors=-1 or all)"
            : "MakeChain: a front distance sensor needs a sensor module in "
              "front of module 0 (sensor after -1; mrsim-scenario new "
              "--sensors=-1 or all): on the sensor module after module " +
                  std::to_string(*sensors.begin()) +
                  " it would face that module and read about 0");
  }

  const Eigen::Vector3d& fs = options.frame_size;
  const ForceSensor plate_defaults;
  const double lift = options.force_sensors ? plate_defaults.size.z() : 0.0;
  const double z = options.origin.z() + fs.z() / 2 + lift;

  // Lay the parts out from the front going towards -x.
  std::vector<Part> parts;
  int sensor_count = 0;
  auto add_sensor = [&]() {
    parts.push_back({true, sensor_count++, fs.x(), 0});
  };
  if (sensors.count(-1)) add_sensor();
  for (int i = 0; i < options.modules; ++i) {
    parts.push_back({false, i, 2 * fs.x(), 0});
    if (sensors.count(i)) add_sensor();
  }
  double cursor = 0;  // front face of the current part
  double module0_center = 0;
  for (Part& part : parts) {
    part.center = cursor - part.length / 2;
    cursor -= part.length;
    if (!part.is_sensor && part.index == 0) module0_center = part.center;
  }
  const double shift = options.origin.x() - module0_center;

  const std::string& name = options.name;
  Robot robot;
  robot.name = name;
  std::vector<std::string> front_guid, back_guid;  // touching guids per part
  for (size_t p = 0; p < parts.size(); ++p) {
    const Part& part = parts[p];
    const Eigen::Vector3d center(part.center + shift, options.origin.y(), z);
    if (!part.is_sensor) {
      const int i = part.index;
      const std::string prefix = name + "/m" + std::to_string(i);
      Module module;
      module.mod_nr = i;
      module.position = center;
      switch (options.pattern) {
        case ChainPattern::kPitch:
          module.axis = Axis::kPitch;
          break;
        case ChainPattern::kYaw:
          module.axis = Axis::kYaw;
          break;
        case ChainPattern::kPitchYaw:
          module.axis = i % 2 == 0 ? Axis::kPitch : Axis::kYaw;
          break;
      }
      for (int f = 0; f < 2; ++f) {
        Frame& frame = module.frames[f];
        frame.guid = prefix + "/f" + std::to_string(f);
        frame.shape = "Box";
        frame.scale = fs;
        frame.position =
            center + Eigen::Vector3d(f == 0 ? fs.x() / 2 : -fs.x() / 2, 0, 0);
        frame.rotation.setZero();
        frame.quat_rotation.setIdentity();
        frame.mass = options.module_mass / 2;
        frame.is_static = false;
        frame.material_name = options.material;
      }
      module.joint.guid = prefix + "/joint";
      module.joint.left_frame_guid = module.frames[0].guid;
      module.joint.right_frame_guid = module.frames[1].guid;
      module.joint.type = JointType::kHinge;
      module.joint.lower_range_limit = -options.joint_limit;
      module.joint.upper_range_limit = options.joint_limit;
      module.joint.kp = options.kp;
      module.joint.max_vel = options.max_vel;
      front_guid.push_back(module.frames[0].guid);
      back_guid.push_back(module.frames[1].guid);
      robot.modules.push_back(module);
    } else {
      const std::string guid = name + "/s" + std::to_string(part.index);
      SensorModule sm;
      sm.guid = guid;
      sm.left_mod_nr = -1;
      sm.right_mod_nr = -1;
      for (size_t q = p; q-- > 0;) {
        if (!parts[q].is_sensor) {
          sm.left_mod_nr = parts[q].index;
          break;
        }
      }
      for (size_t q = p + 1; q < parts.size(); ++q) {
        if (!parts[q].is_sensor) {
          sm.right_mod_nr = parts[q].index;
          break;
        }
      }
      sm.position = center;
      sm.size = fs;
      sm.material_name = options.material;
      sm.force_lock_position = center - Eigen::Vector3d(0, 0, fs.z() / 2);
      sm.distance_lock_position = center + Eigen::Vector3d(fs.x() / 2, 0, 0);
      if (options.force_sensors) {
        ForceSensor plate;
        plate.guid = guid + "/force";
        plate.sensor_position = 0;
        plate.position =
            sm.force_lock_position - Eigen::Vector3d(0, 0, plate.size.z() / 2);
        plate.material_name = options.material;
        sm.force_sensor = plate;
        sm.force_sensor_lock = MakeLock(guid + "/force_lock", guid, plate.guid);
      }
      if (options.front_distance_sensor && part.index == 0) {
        DistanceSensor ray;
        ray.guid = guid + "/d0";
        ray.sensor_position = 4;
        ray.position =
            sm.distance_lock_position + Eigen::Vector3d(ray.size.x() / 2, 0, 0);
        ray.ray_direction = Eigen::Vector3d::UnitX();
        sm.distance_sensors.push_back(ray);
        sm.distance_sensor_locks.push_back(
            MakeLock(guid + "/d0_lock", guid, ray.guid));
      }
      front_guid.push_back(guid);
      back_guid.push_back(guid);
      robot.sensor_modules.push_back(sm);
    }
  }
  for (size_t p = 0; p + 1 < parts.size(); ++p) {
    robot.locks.push_back(MakeLock(name + "/lock" + std::to_string(p),
                                   back_guid[p], front_guid[p + 1]));
  }
  return robot;
}

}  // namespace mrsim
