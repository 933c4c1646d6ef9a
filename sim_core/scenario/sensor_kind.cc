#include "sim_core/scenario/sensor_kind.h"

#include <cmath>

#include "sim_core/scenario/face_geometry.h"
#include "sim_core/scenario/part_look.h"

namespace mrsim {
namespace {

std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// --------------------------------------------------------------- force
// A plate welded to a face; MuJoCo's `force` sensor on it reads what the
// weld carries (N, plate axes), the reading is its magnitude.
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
  k.member = "force_sensor";
  k.inert_fields = {"position", "rotation"};
  k.mount = SensorMount::kPlate;
  k.plate = [](const SensorModule& sm, int) {
    const ForceSensor& f = sm.force_sensor.value();
    const PlatePose pose = ForcePlatePose(sm);
    return SensorPlate{pose.position, pose.rotation, f.size, f.mass,
                       f.material_name};
  };
  k.look = PartLook::kForcePlate;
  k.mujoco = {{"force", ""}};
  k.read = [](const SensorReadInput& in, double* out) {
    const double* f = in.mujoco[0];
    out[0] = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  };
  k.store = [](SensorModuleState& state, int,
               const std::vector<double>& values) {
    state.has_force = true;
    state.force = values[0];
  };
  k.fields = [](SensorModule& sm, int) {
    return FieldsOf(sm.force_sensor.value());
  };
  k.set = [](SensorModule& sm, bool on) {
    if (on == sm.force_sensor.has_value()) return;
    if (on) {
      ForceSensor plate;
      plate.material_name = sm.material_name;
      sm.force_sensor = plate;
    } else {
      sm.force_sensor.reset();
      sm.force_sensor_lock.reset();
    }
  };
  return k;
}

// ------------------------------------------------------------ distance
// A ray from a face along ray_Direction (the face's normal when that is
// zero); the physics casts it, skipping the module and its plate.
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
  k.member = "distance_sensors";
  k.many = true;
  k.inert_fields = {"rotation", "ray_Resolution"};
  k.mount = SensorMount::kRay;
  k.ray = [](const SensorModule& sm, int i) {
    const DistanceSensor& ds = sm.distance_sensors.at(i);
    SensorRay ray;
    ray.face = ds.sensor_position;
    ray.direction = ds.ray_direction;
    if (!(ray.direction.norm() > 0) || !ray.direction.allFinite()) {
      ray.direction = SensorFaceNormal(ds.sensor_position);
    }
    ray.direction.normalize();
    ray.max_range = ds.max_ray_distance;
    ray.look_size = ds.size;
    ray.look_mass = ds.mass;
    return ray;
  };
  k.look = PartLook::kDistanceSensor;
  k.read = [](const SensorReadInput& in, double* out) { out[0] = in.ray; };
  k.store = [](SensorModuleState& state, int face,
               const std::vector<double>& values) {
    state.distances.push_back(values[0]);
    state.distance_faces.push_back(face);
  };
  k.fields = [](SensorModule& sm, int i) {
    return FieldsOf(sm.distance_sensors.at(i));
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
  k.member = "imu";
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

// -------------------------------------------------------------- camera
// A MuJoCo camera at a face's centre looking along the face's normal, the
// picture's up the module's +z (for the top and bottom faces its +x, the
// chain's forward), turned down by `tilt`. No channels: its pictures are
// rendered outside the physics.
SensorKind CameraKind() {
  SensorKind k{"camera",
               "camera",
               PartKind::kCamera,
               Eigen::Vector3d(0.85, 0.3, 0.85),  // magenta
               {}};
  k.count = [](const SensorModule& sm) {
    return static_cast<int>(sm.cameras.size());
  };
  k.face = [](const SensorModule& sm, int i) {
    return sm.cameras.at(i).sensor_position;
  };
  k.member = "cameras";
  k.many = true;
  k.mount = SensorMount::kCamera;
  k.camera = [](const SensorModule& sm, int i) {
    SensorCamera c;
    c.camera = sm.cameras.at(i);
    c.face = c.camera.sensor_position;
    const CameraPose pose = CameraOnFace(c.camera, sm.size);
    c.position = pose.position;
    c.rotation = pose.rotation;
    return c;
  };
  k.fields = [](SensorModule& sm, int i) { return FieldsOf(sm.cameras.at(i)); };
  return k;
}

}  // namespace

const std::vector<SensorKind>& SensorKinds() {
  static const std::vector<SensorKind> kinds = {ForceKind(), DistanceKind(),
                                                ImuKind(), CameraKind()};
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
