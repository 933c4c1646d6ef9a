// The sensor seam: one description per kind of sensor a sensor module can
// carry (force plate, distance sensor, IMU). The schema describes a kind's
// fields (scenario_schema_inl.h); everything else that differs per kind is
// here: how an instance is mounted (a site at the module's centre, a plate
// welded to a face, a ray from a face), the MuJoCo sensors it reads, how
// its values are made and where they land in the state. The MJCF builder,
// the physics read-back, the logger's CSV columns and the studio's
// inspector walk this table instead of naming kinds. docs/architecture.md,
// "Adding a sensor kind", is the recipe. No MJCF text and no LCM in here.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim_core/scenario/part_look.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario/scenario_schema.h"

namespace mrsim {

// One value an instance of a kind reads, e.g. the IMU's "accel.x" (m/s^2).
// An empty name: the kind reads one value, named by the kind alone.
struct SensorChannel {
  const char* name;
  const char* unit;
};

// A MuJoCo sensor a kind puts on its instance's site, e.g. the IMU's
// accelerometer: <accelerometer name="r/sm2/imu/accel" site="r/sm2/imu"/>.
struct SensorMujoco {
  const char* element;  // MJCF sensor element: "accelerometer", "gyro", ...
  const char* suffix;   // appended to the site's name: "accel"
};

// How an instance sits on its sensor module; the MJCF builder and the
// physics handle each mount the same way whatever the kind.
enum class SensorMount {
  // A site at the module's centre with the module's axes (the IMU).
  kCentre,
  // A body of its own welded to the module (SensorKind::plate), a site at
  // its centre: the force plate, whose MuJoCo `force` sensor reads what
  // the weld carries. Its bodies count for the robot's centre of mass and
  // rays of the same module skip them.
  kPlate,
  // A site on a face looking along a direction (SensorKind::ray); the
  // physics casts a ray from it that skips the module and its plates, and
  // hands the distance to `read` (the distance sensor).
  kRay,
  // A MuJoCo <camera> on a face looking out (SensorKind::camera), with a
  // small frustum of marker sites. The physics reads nothing from it: its
  // pictures are rendered from the module's pose by whoever wants them
  // (mrsim-camera, Simulation.camera_image; viewer/camera_image_renderer.h).
  kCamera,
};

// A kPlate instance, in its sensor module's frame.
struct SensorPlate {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // full extents
  double mass = 0.0;
  std::string material = "";
};

// A kRay instance, in its sensor module's frame: from the centre of face
// `face` along `direction` (unit), up to `max_range`. A look box of
// `look_size` and `look_mass` (no collisions) sits on the face when both
// are positive.
struct SensorRay {
  int face = 0;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  double max_range = 0.0;
  Eigen::Vector3d look_size = Eigen::Vector3d::Zero();
  double look_mass = 0.0;
};

// A kCamera instance, in its sensor module's frame: MuJoCo's camera frame
// (x right, y up, looking along -z) at the centre of face `face`.
struct SensorCamera {
  int face = 4;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Camera camera;  // the part: field of view, size, rate, clipping, noise
};

// What `read` gets: the instance, its MuJoCo sensors' values (in
// SensorKind::mujoco order), a ray's distance (kRay), and a key for noise
// that is the same for the same seed, robot, sensor module, instance and
// simulation time.
struct SensorReadInput {
  const SensorModule* sensor_module = nullptr;
  int instance = 0;
  std::vector<const double*> mujoco;
  double ray = 0.0;       // m, kRay only
  double time = 0.0;      // s
  std::uint64_t key = 0;  // robot, sensor module and instance
};

struct SensorKind {
  // In messages, CSV columns and docs: "force", "distance", "imu".
  const char* name;
  const char* label;    // for people: "force plate"
  PartKind part;        // its part in the schema
  Eigen::Vector3d rgb;  // its colour in the studio (part_look.h's hues)
  std::vector<SensorChannel> channels;
  // How many the sensor module carries, and the face of the k-th (0..5),
  // or -1 when it sits on no face (the IMU, at the module's centre).
  int (*count)(const SensorModule& sm) = nullptr;
  int (*face)(const SensorModule& sm, int k) = nullptr;
  // Where the instances live in the scenario: SensorModule's member
  // ("force_sensor", "distance_sensors", "imu") and whether it is a list
  // (the studio's inspector group of the k-th is "distance_sensors[k]").
  const char* member = "";
  bool many = false;
  // Fields the files of the original carry but the physics ignores (a
  // plate's own pose, a ray's resolution): files keep them, the studio does
  // not offer them.
  std::vector<std::string> inert_fields = {};
  // How an instance is mounted, with the plate or ray of the k-th for
  // kPlate and kRay kinds, and the look (part_look.h) of their geoms.
  SensorMount mount = SensorMount::kCentre;
  SensorPlate (*plate)(const SensorModule& sm, int k) = nullptr;
  SensorRay (*ray)(const SensorModule& sm, int k) = nullptr;
  SensorCamera (*camera)(const SensorModule& sm, int k) = nullptr;
  PartLook look = PartLook::kSensorModule;
  // MuJoCo's own sensors on the instance's site (mjcf_names::SensorKindSite):
  // the builder adds them, the physics reads their values and calls `read`
  // for each instance, which fills channels.size() values. A kind with no
  // channels (the camera) has no `read` and nothing in the state.
  std::vector<SensorMujoco> mujoco = {};
  void (*read)(const SensorReadInput& in, double* out) = nullptr;
  // Where the values land in the state. nullptr: a SensorReading in
  // SensorModuleState::readings (the message's `readings`, any kind).
  // Force and distance store into fields of their own (`force`,
  // `distance`), whose wire layout recorded logs and controllers rely on.
  void (*store)(SensorModuleState& state, int face,
                const std::vector<double>& values) = nullptr;
  // For the studio: the k-th instance's fields (the schema's FieldsOf),
  // and, for kinds a module carries at most one of, putting one on or
  // taking it off. A kPlate kind changes how the chain rests, so the
  // studio lays the robot out again after `set`.
  std::vector<FieldRef> (*fields)(SensorModule& sm, int k) = nullptr;
  void (*set)(SensorModule& sm, bool on) = nullptr;
};

// Every kind, in the order readings and columns list them.
const std::vector<SensorKind>& SensorKinds();
// nullptr when no kind has that name (a reading from a newer sender).
const SensorKind* FindSensorKind(std::string_view name);

// The column (and plot) name of one value: "<prefix>.<kind><face>" plus
// ".<channel>" when the channel is named, e.g. "sensor_module0.force",
// "sensor_module0.distance4", "sensor_module0.imu.accel.x". face < 0: none.
std::string SensorValueName(const std::string& prefix, const SensorKind& kind,
                            int face, const SensorChannel& channel);

// Deterministic white noise: a standard normal value from a key and a
// channel (splitmix64 and Box-Muller; the same on every platform).
double StandardNormal(std::uint64_t key, int channel);

}  // namespace mrsim
