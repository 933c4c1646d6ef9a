// The sensor seam: one description per kind of sensor a sensor module can
// carry (force plate, distance sensor, IMU). The schema describes a kind's
// fields (scenario_schema_inl.h); everything else that differs per kind is
// here, and the MJCF builder, the physics read-back, the state message
// codec, the logger's CSV columns and the studio consult this table instead
// of naming kinds. docs/architecture.md, "Adding a sensor kind", is the
// recipe. No MJCF text and no LCM in here.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sim_core/scenario.h"
#include "sim_core/scenario_schema.h"

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

// Where a reading comes from when the kind reads MuJoCo sensors: the
// instance, its MuJoCo sensors' values (in SensorKind::mujoco order), and
// a key for noise that is the same for the same seed, robot, sensor module,
// instance and simulation time.
struct SensorReadInput {
  const SensorModule* sensor_module = nullptr;
  int instance = 0;
  std::vector<const double*> mujoco;
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
  // Kinds read through MuJoCo's own sensors: the builder puts a site at
  // the sensor module's centre (mjcf_names::SensorKindSite) with these
  // sensors on it, and the physics calls `read` for each instance with
  // their values, filling channels.size() values. Readings of such kinds
  // travel in SensorModuleState::readings and the message's `readings`.
  // Empty for force and distance, whose plate and rays the builder and
  // physics make themselves and whose readings have fields of their own.
  std::vector<SensorMujoco> mujoco = {};
  void (*read)(const SensorReadInput& in, double* out) = nullptr;
  // For the studio, kinds with no geometry of their own (the IMU): the
  // k-th instance's fields (the schema's FieldsOf) and putting one on or
  // taking it off. nullptr for force and distance, which the studio lays
  // out on the module's faces itself.
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
