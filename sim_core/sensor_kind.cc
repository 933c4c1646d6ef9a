#include "sim_core/sensor_kind.h"

#include <cmath>

#include "sim_core/part_look.h"

namespace mrsim {
namespace {

std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// --------------------------------------------------------------- force
SensorKind ForceKind() {
  SensorKind k{"force",
               "force plate",
               PartKind::kForceSensor,
               PartLookRgb(PartLook::kForcePlate),
               {{"", "N"}}};
  k.count = [](const SensorModule& sm) { return sm.force_sensor ? 1 : 0; };
  k.face = [](const SensorModule& sm, int) {
    return sm.force_sensor ? sm.force_sensor->sensor_position : -1;
  };
  return k;
}

// ------------------------------------------------------------ distance
SensorKind DistanceKind() {
  SensorKind k{"distance",
               "distance sensor",
               PartKind::kDistanceSensor,
               PartLookRgb(PartLook::kDistanceSensor),
               {{"", "m"}}};
  k.count = [](const SensorModule& sm) {
    return static_cast<int>(sm.distance_sensors.size());
  };
  k.face = [](const SensorModule& sm, int i) {
    return sm.distance_sensors.at(i).sensor_position;
  };
  return k;
}

// ----------------------------------------------------------------- imu
// MuJoCo's accelerometer reads specific force in its site's frame (at rest
// +g along up) and its gyro the angular velocity; the site is the module's
// centre with the module's axes, so both are in the module's frame.
SensorKind ImuKind() {
  SensorKind k{"imu",
               "IMU",
               PartKind::kImu,
               Eigen::Vector3d(0.2, 0.85, 0.9),  // cyan
               {{"accel.x", "m/s^2"},
                {"accel.y", "m/s^2"},
                {"accel.z", "m/s^2"},
                {"gyro.x", "rad/s"},
                {"gyro.y", "rad/s"},
                {"gyro.z", "rad/s"}}};
  k.count = [](const SensorModule& sm) { return sm.imu ? 1 : 0; };
  k.face = [](const SensorModule&, int) { return -1; };
  k.mujoco = {{"accelerometer", "accel"}, {"gyro", "gyro"}};
  k.read = [](const SensorReadInput& in, double* out) {
    const Imu& imu = *in.sensor_module->imu;
    // The same seed and time give the same noise on every run; the key
    // keeps two IMUs of one seed apart.
    const std::uint64_t key =
        SplitMix64(in.key ^ SplitMix64(static_cast<std::uint64_t>(imu.seed)) ^
                   static_cast<std::uint64_t>(std::llround(in.time * 1e6)));
    for (int i = 0; i < 3; ++i) {
      out[i] = in.mujoco[0][i] + imu.accel_bias[i];
      out[3 + i] = in.mujoco[1][i] + imu.gyro_bias[i];
      if (imu.accel_noise > 0) {
        out[i] += imu.accel_noise * StandardNormal(key, i);
      }
      if (imu.gyro_noise > 0) {
        out[3 + i] += imu.gyro_noise * StandardNormal(key, 3 + i);
      }
    }
  };
  k.fields = [](SensorModule& sm, int) { return FieldsOf(sm.imu.value()); };
  k.set = [](SensorModule& sm, bool on) {
    if (on == sm.imu.has_value()) return;
    sm.imu = on ? std::optional<Imu>(Imu{}) : std::nullopt;
  };
  return k;
}

}  // namespace

const std::vector<SensorKind>& SensorKinds() {
  static const std::vector<SensorKind> kinds = {ForceKind(), DistanceKind(),
                                                ImuKind()};
  return kinds;
}

const SensorKind* FindSensorKind(std::string_view name) {
  for (const SensorKind& k : SensorKinds()) {
    if (name == k.name) return &k;
  }
  return nullptr;
}

std::string SensorValueName(const std::string& prefix, const SensorKind& kind,
                            int face, const SensorChannel& channel) {
  std::string name = prefix + "." + kind.name;
  if (face >= 0) name += std::to_string(face);
  if (channel.name[0] != '\0') name += std::string(".") + channel.name;
  return name;
}

double StandardNormal(std::uint64_t key, int channel) {
  const std::uint64_t a = SplitMix64(key * 2654435761u + 2 * channel + 1);
  const std::uint64_t b = SplitMix64(a ^ 0x5851f42d4c957f2dull);
  // Two uniforms in (0, 1] and [0, 1) from the top 53 bits.
  const double u1 = (static_cast<double>(a >> 11) + 1.0) * 0x1.0p-53;
  const double u2 = static_cast<double>(b >> 11) * 0x1.0p-53;
  constexpr double kTwoPi = 6.283185307179586;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

}  // namespace mrsim
