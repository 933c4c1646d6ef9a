// The scenario model: plain data describing robots, terrain, scene objects and
// contact materials, usable with no physics running. Field names follow the
// original MRSim XML layout (domain.md section 3); units are SI, angles of
// joint limits in radians, Euler rotations in degrees (as MRSim stored them).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "sim_core/scenario/optimization_settings.h"
#include "sim_core/scenario/run_settings.h"

namespace mrsim {

// Which axis convention positions and rotations in a file use. Files say it
// explicitly (root attribute frame="z-up" or frame="unity-y-up"); the model
// in memory is always kZUp.
enum class FrameConvention { kZUp, kUnityYUp };

enum class Axis { kPitch, kYaw };
enum class JointType { kHinge, kLock };
enum class PrimitiveShape { kBox, kSphere, kCylinder, kCapsule };

// A rigid body of a module: a Box (full extents = scale) or a mesh file
// (OBJ/STL, path relative to the scenario file, scaled by scale).
struct Frame {
  std::string guid;
  std::string shape = "Box";  // "Box" or a mesh path
  Eigen::Vector3d scale = Eigen::Vector3d(0.05, 0.05, 0.05);
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  // Euler, degrees
  Eigen::Quaterniond quat_rotation = Eigen::Quaterniond::Identity();
  double mass = 0.1;
  bool is_static = false;
  std::string material_name = "plastic";

  bool is_mesh() const { return shape != "Box"; }
};

// A connection between two frames: a motorised hinge (position servo as a P
// law on speed) or a rigid lock. Limits in rad, max_vel in rad/s. The servo
// commands speed = clamp(kp * (target - angle), +-max_vel) and a velocity
// loop of gain velocity_gain drives the hinge towards it with at most
// max_torque, as a hobby servo's stall torque limits it. A module's hinge
// always has that servo; a loose hinge (Scenario::loose_joints) has it only
// when `servo` is set, and turns freely otherwise.
struct Joint {
  std::string guid;
  std::string left_frame_guid;
  std::string right_frame_guid;
  JointType type = JointType::kHinge;
  double lower_range_limit = -1.5708;
  double upper_range_limit = 1.5708;
  double kp = 10.0;
  double max_vel = 3.0;
  double velocity_gain = 5.0;  // N m s/rad, hinge only
  double max_torque = 2.0;     // N m, hinge only (stall torque)
  double break_force = 0.0;    // N, lock only; 0: never breaks
  bool servo = false;          // loose hinge only: driven by the servo above
};

// A module's frames[i] in words: frames[0] is on the +x side, the front,
// frames[1] the back (chain_builder.h). Messages and the studio's
// inspector name frames so, never "frame 0".
inline const char* FrameName(int i) {
  return i == 0 ? "front frame" : i == 1 ? "back frame" : "frame";
}

// Two frames joined by a hinge whose axis is given by `axis`.
struct Module {
  int mod_nr = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Axis axis = Axis::kPitch;
  std::array<Frame, 2> frames;
  Joint joint;
  // Both frames carry passive wheels: they roll along their x axis (the
  // chain) and grip across it (docs/physics.md, "Directional friction").
  bool passive_wheels = false;
};

// A plate locked to one face of a sensor module; reads the magnitude of the
// force carried by that lock. sensor_position: 0 bottom, 1 left, 2 top,
// 3 right.
struct ForceSensor {
  std::string guid;
  double force_value = 0.0;
  int sensor_position = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  std::string material_name = "plastic";
  double mass = 0.005;
  Eigen::Vector3d size = Eigen::Vector3d(0.04, 0.04, 0.002);
};

// A ray from one face (0..5) of a sensor module along ray_direction (in the
// sensor module's frame); reads the distance to the first hit or
// max_ray_distance.
struct DistanceSensor {
  std::string guid;
  int sensor_position = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond quat_rotation = Eigen::Quaterniond::Identity();
  double mass = 0.001;
  Eigen::Vector3d size = Eigen::Vector3d(0.01, 0.01, 0.01);
  double max_ray_distance = 2.0;
  Eigen::Vector3d ray_direction = Eigen::Vector3d::UnitX();
  double ray_resolution = 1.0;  // sampling step along the ray (m)
};

// An inertial measurement unit at the centre of a sensor module: a 3-axis
// accelerometer (specific force, m/s^2: a module at rest reads +9.81 along
// its up axis) and a 3-axis gyroscope (rad/s), both in the module's own
// frame, read from MuJoCo's accelerometer and gyro sensors. Each reading
// adds `*_bias` and white noise of standard deviation `*_noise`, drawn from
// `seed` and the simulation time: the same seed gives the same readings.
struct Imu {
  std::string guid;
  double accel_noise = 0.0;                              // m/s^2
  double gyro_noise = 0.0;                               // rad/s
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // m/s^2
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // rad/s
  int seed = 0;
};

// A camera on a face of a sensor module (or of the box around a scene
// object), looking out along the face's normal (tilted by `tilt` about its
// horizontal axis): what the robot sees, or, on a static scene object, a
// fixed view of the world, rendered by mrsim-camera or
// Simulation.camera_image from its part's pose at `rate` pictures per
// simulated second. Pixel noise of standard deviation `noise` (grey
// levels, 0..255) is drawn from `seed`, the state's seq and the pixel: the
// same seed gives the same pictures (docs/camera.md).
struct Camera {
  std::string guid;
  int sensor_position = 4;  // front
  double fovy = 60.0;       // deg, vertical field of view
  int width = 160;          // px
  int height = 120;         // px
  double rate = 30.0;       // pictures per simulated second
  double near_clip = 0.01;  // m
  double far_clip = 10.0;   // m
  double tilt = 0.0;        // deg, positive looks down
  double noise = 0.0;       // grey levels
  int seed = 0;
};

// A box between two modules (left_mod_nr/right_mod_nr, -1 = chain end)
// carrying at most one force sensor, up to six distance sensors, at most
// one IMU and up to six cameras (the kinds: sensor_kind.h).
struct SensorModule {
  std::string guid;
  int left_mod_nr = -1;
  int right_mod_nr = -1;
  std::optional<ForceSensor> force_sensor;
  std::optional<Joint> force_sensor_lock;
  Eigen::Vector3d force_lock_position = Eigen::Vector3d::Zero();
  std::vector<DistanceSensor> distance_sensors;
  Eigen::Vector3d distance_lock_position = Eigen::Vector3d::Zero();
  std::vector<Joint> distance_sensor_locks;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d(0.05, 0.05, 0.05);
  Eigen::Quaterniond quat_rotation = Eigen::Quaterniond::Identity();
  double mass = 0.05;
  std::string material_name = "plastic";
  std::optional<Imu> imu;
  std::vector<Camera> cameras;
};

// A chain of modules with sensor modules between them. `locks` are the rigid
// joints between consecutive parts (frame guids, or a sensor module guid).
struct Robot {
  std::string name;  // unique in the scenario; used in LCM channel names
  std::vector<Module> modules;
  std::vector<SensorModule> sensor_modules;
  std::vector<Joint> locks;
};

// Terrain: a height field from a grey-scale image, or a flat plane when
// height_image is empty. height_image is a path (relative to the scenario
// file) or base64-encoded image bytes ("base64:" prefix optional when the
// string does not name a file). position is the terrain's corner.
struct Scene {
  std::string guid;
  std::string height_image;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string material_name = "ground";
  double height = 0.0;             // height of the brightest pixel (m)
  double meters_per_pixel = 0.05;  // horizontal extent of one pixel (m)
};

// A free-standing primitive: obstacle, ball, ramp. For Box, size is the full
// extents; Sphere uses size.x as diameter; Cylinder/Capsule size.x diameter
// and size.z length.
struct SceneObject {
  std::string guid;
  Eigen::Vector3d size = Eigen::Vector3d(0.1, 0.1, 0.1);
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond quat_rotation = Eigen::Quaterniond::Identity();
  std::string material_name = "plastic";
  PrimitiveShape shape = PrimitiveShape::kBox;
  double mass = 0.1;
  bool is_static = false;
  // Up to six, one per face of the box around the object (SceneObjectBox,
  // face_geometry.h); on a static object, a fixed camera on the world.
  std::vector<Camera> cameras;
};

// Contact parameters for a pair of materials (order does not matter).
struct ContactFriction {
  std::string material1;
  std::string material2;
  double restitution = 0.0;
  double friction = 0.5;
  double youngs_modulus = 1e6;
  // Directional friction (docs/physics.md): when set, sliding friction is
  // forward_friction / backward_friction along the +x / -x axis of the
  // material1 part's own frame and lateral_friction across it, instead of
  // `friction`; torsional (> 0: spin friction) and rolling (> 0: rolling
  // friction) are lengths in m.
  bool directional = false;
  double forward_friction = 0.5;
  double backward_friction = 0.5;
  double lateral_friction = 0.5;
  double torsional_friction = 0.0;
  double rolling_friction = 0.0;
};

enum class FluidKind { kWater, kAir };

// An axis-aligned box region of fluid: water gives buoyancy and drag, air
// gives drag (optionally with wind velocity).
struct FluidRegion {
  std::string guid;
  FluidKind kind = FluidKind::kWater;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centre
  Eigen::Vector3d size = Eigen::Vector3d(1, 1, 1);     // full extents
  double density = 1000.0;                             // kg/m^3
  double viscosity = 0.0009;                           // Pa s
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // flow/wind m/s

  // Water's density and viscosity are the defaults above; air's:
  static constexpr double kAirDensity = 1.2;       // kg/m^3
  static constexpr double kAirViscosity = 1.8e-5;  // Pa s
};

// Physics settings that are not part of the robot.
struct SimulationSettings {
  double timestep = 0.002;  // s
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);
};

// The names parts outside any robot go by in MJCF names ("scene/obj2",
// "loose/sm0") and as the owner of their cameras (camera_image_t.robot,
// the channel <prefix>_CAMERA_scene; docs/camera.md): no robot may take
// them.
inline constexpr char kSceneOwnerName[] = "scene";
inline constexpr char kLooseOwnerName[] = "loose";

// Everything needed to start a simulation. Frames, joints, sensor modules
// and scene objects may also appear without a robot (loose_* lists).
struct Scenario {
  std::vector<Robot> robots;
  Scene scene;
  std::vector<SceneObject> scene_objects;
  std::vector<ContactFriction> contact_frictions;
  std::vector<FluidRegion> fluid_regions;
  SimulationSettings settings;
  // How to run it (clock, rate, controller); none: as mrsim-sim defaults.
  std::optional<RunSettings> run;
  // How to optimise it (mrsim-opt FILE, the studio's Optimise); none: as
  // mrsim-opt's flags default.
  std::optional<OptimizationSettings> optimization;
  std::vector<Frame> loose_frames;
  std::vector<Joint> loose_joints;
  std::vector<SensorModule> loose_sensor_modules;

  // Directory of the file it was read from; relative mesh and image paths
  // resolve against it. Not written to XML.
  std::string base_dir;
};

// Exact, field-by-field equality over the fields and children the schema
// lists (scenario_schema_inl.h; doubles with ==, quaternions by
// coefficients), as the XML round trip promises. Scenario::base_dir is
// where a file was read from, not content, and is not compared.
bool operator==(const Frame& a, const Frame& b);
bool operator==(const Joint& a, const Joint& b);
bool operator==(const Module& a, const Module& b);
bool operator==(const ForceSensor& a, const ForceSensor& b);
bool operator==(const DistanceSensor& a, const DistanceSensor& b);
bool operator==(const Imu& a, const Imu& b);
bool operator==(const Camera& a, const Camera& b);
bool operator==(const SensorModule& a, const SensorModule& b);
bool operator==(const Robot& a, const Robot& b);
bool operator==(const Scene& a, const Scene& b);
bool operator==(const SceneObject& a, const SceneObject& b);
bool operator==(const ContactFriction& a, const ContactFriction& b);
bool operator==(const FluidRegion& a, const FluidRegion& b);
bool operator==(const SimulationSettings& a, const SimulationSettings& b);
bool operator==(const Scenario& a, const Scenario& b);
inline bool operator!=(const Frame& a, const Frame& b) { return !(a == b); }
inline bool operator!=(const Joint& a, const Joint& b) { return !(a == b); }
inline bool operator!=(const Module& a, const Module& b) { return !(a == b); }
inline bool operator!=(const ForceSensor& a, const ForceSensor& b) {
  return !(a == b);
}
inline bool operator!=(const DistanceSensor& a, const DistanceSensor& b) {
  return !(a == b);
}
inline bool operator!=(const Imu& a, const Imu& b) { return !(a == b); }
inline bool operator!=(const Camera& a, const Camera& b) { return !(a == b); }
inline bool operator!=(const SensorModule& a, const SensorModule& b) {
  return !(a == b);
}
inline bool operator!=(const Robot& a, const Robot& b) { return !(a == b); }
inline bool operator!=(const Scene& a, const Scene& b) { return !(a == b); }
inline bool operator!=(const SceneObject& a, const SceneObject& b) {
  return !(a == b);
}
inline bool operator!=(const ContactFriction& a, const ContactFriction& b) {
  return !(a == b);
}
inline bool operator!=(const FluidRegion& a, const FluidRegion& b) {
  return !(a == b);
}
inline bool operator!=(const SimulationSettings& a,
                       const SimulationSettings& b) {
  return !(a == b);
}
inline bool operator!=(const Scenario& a, const Scenario& b) {
  return !(a == b);
}

// Frame conventions (docs/scenario.md). Unity is Y-up and left-handed; the
// model is Z-up and right-handed. Positions, sizes, scales and directions
// swap y and z; quaternions (x,y,z,w) become (-x,-z,-y,w); Euler angles
// (x,y,z) become (-x,-z,-y). Each function is the other's exact inverse.
// The schema (scenario_schema.h) says which fields are which.
void ConvertUnityToZUp(Scenario* scenario);
void ConvertZUpToUnity(Scenario* scenario);

// Multiplies every length (positions, sizes, scales, lock positions, ray
// range and step, terrain height and pixel size, fluid regions and flow
// velocity) by `factor`, e.g. to turn Unity scene units into metres.
// Gravity is a physical constant, not a scene size: it, masses, angles and
// directions are unchanged. Which fields are lengths is in the schema
// (scenario_schema.h).
void ScaleLengths(Scenario* scenario, double factor);

// The name a robot goes by in channels, MJCF and messages: Robot::name, or
// "robot<i>" when it is empty. Throws std::out_of_range for a bad index.
std::string RobotName(const Scenario& scenario, int robot);

const char* ToString(Axis axis);
const char* ToString(JointType type);
const char* ToString(PrimitiveShape shape);
const char* ToString(FluidKind kind);
const char* ToString(FrameConvention frame);

}  // namespace mrsim
