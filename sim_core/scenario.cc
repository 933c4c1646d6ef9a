#include "sim_core/scenario.h"

#include <functional>
#include <utility>

namespace mrsim {

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
         a.frames == b.frames && a.joint == b.joint;
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
         a.youngs_modulus == b.youngs_modulus;
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

namespace {

// Applies the per-field maps of a frame change or a unit scale to every
// part of a scenario, so the two conversions cannot miss a field.
struct FieldMap {
  // Positions, sizes, scales, directions.
  std::function<void(Eigen::Vector3d*, bool is_length)> vector;
  std::function<void(Eigen::Quaterniond*)> quat;
  std::function<void(Eigen::Vector3d*)> euler;
  std::function<void(double*)> length;
};

void Apply(const FieldMap& m, Frame* f) {
  m.vector(&f->scale, true);
  m.vector(&f->position, true);
  m.euler(&f->rotation);
  m.quat(&f->quat_rotation);
}

void Apply(const FieldMap& m, SensorModule* s) {
  if (s->force_sensor) {
    ForceSensor& fs = *s->force_sensor;
    m.vector(&fs.position, true);
    m.quat(&fs.rotation);
    m.vector(&fs.size, true);
  }
  m.vector(&s->force_lock_position, true);
  for (DistanceSensor& d : s->distance_sensors) {
    m.vector(&d.position, true);
    m.euler(&d.rotation);
    m.quat(&d.quat_rotation);
    m.vector(&d.size, true);
    m.length(&d.max_ray_distance);
    m.vector(&d.ray_direction, false);
  }
  m.vector(&s->distance_lock_position, true);
  m.vector(&s->position, true);
  m.euler(&s->rotation);
  m.vector(&s->size, true);
  m.quat(&s->quat_rotation);
}

void Apply(const FieldMap& m, Scenario* s) {
  for (Robot& robot : s->robots) {
    for (Module& module : robot.modules) {
      m.vector(&module.position, true);
      for (Frame& frame : module.frames) Apply(m, &frame);
    }
    for (SensorModule& sm : robot.sensor_modules) Apply(m, &sm);
  }
  m.vector(&s->scene.position, true);
  m.length(&s->scene.height);
  m.length(&s->scene.meters_per_pixel);
  for (SceneObject& o : s->scene_objects) {
    m.vector(&o.size, true);
    m.vector(&o.position, true);
    m.euler(&o.rotation);
    m.quat(&o.quat_rotation);
  }
  for (FluidRegion& r : s->fluid_regions) {
    m.vector(&r.position, true);
    m.vector(&r.size, true);
    m.vector(&r.velocity, true);
  }
  m.vector(&s->settings.gravity, true);
  for (Frame& frame : s->loose_frames) Apply(m, &frame);
  for (SensorModule& sm : s->loose_sensor_modules) Apply(m, &sm);
}

// Swapping y and z is its own inverse, so one map serves both directions.
FieldMap SwapYZ() {
  FieldMap m;
  m.vector = [](Eigen::Vector3d* v, bool) { std::swap((*v)[1], (*v)[2]); };
  m.quat = [](Eigen::Quaterniond* q) {
    const double x = q->x(), y = q->y(), z = q->z();
    q->x() = -x;
    q->y() = -z;
    q->z() = -y;
  };
  m.euler = [](Eigen::Vector3d* e) {
    const double x = (*e)[0], y = (*e)[1], z = (*e)[2];
    *e = Eigen::Vector3d(-x, -z, -y);
  };
  m.length = [](double*) {};
  return m;
}

}  // namespace

void ConvertUnityToZUp(Scenario* scenario) { Apply(SwapYZ(), scenario); }

void ConvertZUpToUnity(Scenario* scenario) { Apply(SwapYZ(), scenario); }

void ScaleLengths(Scenario* scenario, double factor) {
  FieldMap m;
  m.vector = [factor](Eigen::Vector3d* v, bool is_length) {
    if (is_length) *v *= factor;
  };
  m.quat = [](Eigen::Quaterniond*) {};
  m.euler = [](Eigen::Vector3d*) {};
  m.length = [factor](double* x) { *x *= factor; };
  Apply(m, scenario);
}

}  // namespace mrsim
