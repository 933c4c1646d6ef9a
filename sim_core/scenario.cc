#include "sim_core/scenario.h"

#include "sim_core/scenario_schema_inl.h"

namespace mrsim {

std::string RobotName(const Scenario& scenario, int robot) {
  const std::string& name = scenario.robots.at(robot).name;
  return name.empty() ? "robot" + std::to_string(robot) : name;
}

const char* ToString(Axis axis) {
  return axis == Axis::kPitch ? "Pitch" : "Yaw";
}

const char* ToString(JointType type) {
  return type == JointType::kHinge ? "Hinge" : "Lock";
}

const char* ToString(PrimitiveShape shape) {
  switch (shape) {
    case PrimitiveShape::kBox:
      return "Box";
    case PrimitiveShape::kSphere:
      return "Sphere";
    case PrimitiveShape::kCylinder:
      return "Cylinder";
    case PrimitiveShape::kCapsule:
      return "Capsule";
  }
  return "Box";
}

const char* ToString(FluidKind kind) {
  return kind == FluidKind::kWater ? "Water" : "Air";
}

const char* ToString(FrameConvention frame) {
  return frame == FrameConvention::kZUp ? "z-up" : "unity-y-up";
}

}  // namespace mrsim

namespace mrsim {
namespace {

bool QuatEq(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.coeffs() == b.coeffs();
}

}  // namespace

bool operator==(const Frame& a, const Frame& b) {
  return a.guid == b.guid && a.shape == b.shape && a.scale == b.scale &&
         a.position == b.position && a.rotation == b.rotation &&
         QuatEq(a.quat_rotation, b.quat_rotation) && a.mass == b.mass &&
         a.is_static == b.is_static && a.material_name == b.material_name;
}

bool operator==(const Joint& a, const Joint& b) {
  return a.guid == b.guid && a.left_frame_guid == b.left_frame_guid &&
         a.right_frame_guid == b.right_frame_guid && a.type == b.type &&
         a.lower_range_limit == b.lower_range_limit &&
         a.upper_range_limit == b.upper_range_limit && a.kp == b.kp &&
         a.max_vel == b.max_vel && a.velocity_gain == b.velocity_gain &&
         a.max_torque == b.max_torque && a.break_force == b.break_force;
}

bool operator==(const Module& a, const Module& b) {
  return a.mod_nr == b.mod_nr && a.position == b.position && a.axis == b.axis &&
         a.frames == b.frames && a.joint == b.joint &&
         a.passive_wheels == b.passive_wheels;
}

bool operator==(const ForceSensor& a, const ForceSensor& b) {
  return a.guid == b.guid && a.force_value == b.force_value &&
         a.sensor_position == b.sensor_position && a.position == b.position &&
         QuatEq(a.rotation, b.rotation) && a.material_name == b.material_name &&
         a.mass == b.mass && a.size == b.size;
}

bool operator==(const DistanceSensor& a, const DistanceSensor& b) {
  return a.guid == b.guid && a.sensor_position == b.sensor_position &&
         a.position == b.position && a.rotation == b.rotation &&
         QuatEq(a.quat_rotation, b.quat_rotation) && a.mass == b.mass &&
         a.size == b.size && a.max_ray_distance == b.max_ray_distance &&
         a.ray_direction == b.ray_direction &&
         a.ray_resolution == b.ray_resolution;
}

bool operator==(const SensorModule& a, const SensorModule& b) {
  return a.guid == b.guid && a.left_mod_nr == b.left_mod_nr &&
         a.right_mod_nr == b.right_mod_nr && a.force_sensor == b.force_sensor &&
         a.force_sensor_lock == b.force_sensor_lock &&
         a.force_lock_position == b.force_lock_position &&
         a.distance_sensors == b.distance_sensors &&
         a.distance_lock_position == b.distance_lock_position &&
         a.distance_sensor_locks == b.distance_sensor_locks &&
         a.position == b.position && a.rotation == b.rotation &&
         a.size == b.size && QuatEq(a.quat_rotation, b.quat_rotation) &&
         a.mass == b.mass && a.material_name == b.material_name;
}

bool operator==(const Robot& a, const Robot& b) {
  return a.name == b.name && a.modules == b.modules &&
         a.sensor_modules == b.sensor_modules && a.locks == b.locks;
}

bool operator==(const Scene& a, const Scene& b) {
  return a.guid == b.guid && a.height_image == b.height_image &&
         a.position == b.position && a.material_name == b.material_name &&
         a.height == b.height && a.meters_per_pixel == b.meters_per_pixel;
}

bool operator==(const SceneObject& a, const SceneObject& b) {
  return a.guid == b.guid && a.size == b.size && a.position == b.position &&
         a.rotation == b.rotation && QuatEq(a.quat_rotation, b.quat_rotation) &&
         a.material_name == b.material_name && a.shape == b.shape &&
         a.mass == b.mass && a.is_static == b.is_static;
}

bool operator==(const ContactFriction& a, const ContactFriction& b) {
  return a.material1 == b.material1 && a.material2 == b.material2 &&
         a.restitution == b.restitution && a.friction == b.friction &&
         a.youngs_modulus == b.youngs_modulus &&
         a.directional == b.directional &&
         a.forward_friction == b.forward_friction &&
         a.backward_friction == b.backward_friction &&
         a.lateral_friction == b.lateral_friction &&
         a.torsional_friction == b.torsional_friction &&
         a.rolling_friction == b.rolling_friction;
}

bool operator==(const FluidRegion& a, const FluidRegion& b) {
  return a.guid == b.guid && a.kind == b.kind && a.position == b.position &&
         a.size == b.size && a.density == b.density &&
         a.viscosity == b.viscosity && a.velocity == b.velocity;
}

bool operator==(const SimulationSettings& a, const SimulationSettings& b) {
  return a.timestep == b.timestep && a.gravity == b.gravity;
}

bool operator==(const Scenario& a, const Scenario& b) {
  return a.robots == b.robots && a.scene == b.scene &&
         a.scene_objects == b.scene_objects &&
         a.contact_frictions == b.contact_frictions &&
         a.fluid_regions == b.fluid_regions && a.settings == b.settings &&
         a.loose_frames == b.loose_frames && a.loose_joints == b.loose_joints &&
         a.loose_sensor_modules == b.loose_sensor_modules;
}

void ConvertUnityToZUp(Scenario* scenario) {
  schema::GeometryMap m;
  m.swap_yz = true;
  schema::Describe(m, *scenario);
}

// Swapping y and z is its own inverse.
void ConvertZUpToUnity(Scenario* scenario) { ConvertUnityToZUp(scenario); }

void ScaleLengths(Scenario* scenario, double factor) {
  schema::GeometryMap m;
  m.scale = factor;
  schema::Describe(m, *scenario);
}

}  // namespace mrsim
