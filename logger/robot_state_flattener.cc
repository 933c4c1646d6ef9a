#include "logger/robot_state_flattener.h"

#include <stdexcept>

#include "lcmtypes/runtime/decode.h"
#include "logger/csv_format.h"
#include "sim_core/scenario/sensor_kind.h"

namespace mrsim {
namespace {

const char* const kPoseNames[] = {"x", "y", "z", "qw", "qx", "qy", "qz"};

void AppendPose(const pose_t& p, CsvCells& out) {
  for (double v : p.position) out.CommaDouble(v);
  for (double v : p.orientation) out.CommaDouble(v);
}

void PoseNames(const std::string& prefix, std::vector<std::string>* names) {
  for (const char* n : kPoseNames) names->push_back(prefix + "." + n);
}

}  // namespace

namespace {

const LcmStruct& RobotStateType(const LcmTypeRegistry& registry) {
  const LcmStruct* type = registry.FindByName("mrsim.robot_state_t");
  if (type == nullptr ||
      registry.Fingerprint(*type) != robot_state_t::getHash()) {
    throw std::runtime_error(
        "robot_state_t.lcm does not match the compiled robot_state_t");
  }
  return *type;
}

}  // namespace

RobotStateFlattener::RobotStateFlattener(const LcmTypeRegistry& registry) {
  RobotStateType(registry);  // throws when the definitions differ
}

bool RobotStateFlattener::Flatten(const uint8_t* data, size_t size,
                                  FlatRow* row) {
  // Bounds-checked before lcm-gen's decode, which trusts every length.
  if (!DecodeMessage(data, size, &msg_)) return false;
  const robot_state_t& m = msg_;
  shape_.clear();
  shape_.push_back(m.num_modules);
  shape_.push_back(m.num_frames);
  shape_.push_back(m.num_joints);
  shape_.push_back(m.num_sensor_modules);
  for (const sensor_module_state_t& s : m.sensor_modules) {
    shape_.push_back(s.has_force ? 1 : 0);
    shape_.push_back(s.num_distances);
    for (int8_t face : s.distance_face) shape_.push_back(face);
    shape_.push_back(s.num_readings);
    for (const sensor_reading_t& r : s.readings) {
      shape_.push_back(r.face);
      shape_.push_back(r.num_values);
      const SensorKind* kind = FindSensorKind(r.kind);
      shape_.push_back(kind == nullptr ? -1
                                       : static_cast<int>(kind - kinds_base_));
    }
  }
  shape_.push_back(m.num_locks);
  if (!have_shape_ || shape_ != last_shape_ || m.lock_names != last_locks_) {
    last_shape_ = shape_;
    last_locks_ = m.lock_names;
    have_shape_ = true;
    SetColumns(ColumnNames());
  }

  std::string& out = row->values;
  out.clear();
  AppendDouble(SecondsFromUtime(m.utime), &out);
  out.push_back(',');
  AppendInt(m.seq, &out);
  out.push_back(',');
  AppendCsvText(m.robot, &out);
  out.push_back(',');
  CsvCells cells(&out);
  cells.Double(m.sim_time);
  const bool frames_per_module = m.num_frames == 2 * m.num_modules;
  const bool joint_per_module = m.num_joints == m.num_modules;
  for (int i = 0; i < m.num_modules; ++i) {
    AppendPose(m.modules[i], cells);
    if (frames_per_module) {
      AppendPose(m.frames[2 * i], cells);
      AppendPose(m.frames[2 * i + 1], cells);
    }
    if (joint_per_module) {
      const joint_state_t& j = m.joints[i];
      for (double v : {j.angle, j.speed, j.torque}) {
        cells.CommaDouble(v);
      }
      AppendPose(j.world, cells);
    }
  }
  if (!frames_per_module) {
    for (const pose_t& f : m.frames) AppendPose(f, cells);
  }
  if (!joint_per_module) {
    for (const joint_state_t& j : m.joints) {
      for (double v : {j.angle, j.speed, j.torque}) {
        cells.CommaDouble(v);
      }
      AppendPose(j.world, cells);
    }
  }
  for (const sensor_module_state_t& s : m.sensor_modules) {
    AppendPose(s.pose, cells);
    if (s.has_force) {
      cells.CommaDouble(s.force);
    }
    for (double d : s.distance) {
      cells.CommaDouble(d);
    }
    for (const sensor_reading_t& r : s.readings) {
      for (double v : r.values) cells.CommaDouble(v);
    }
  }
  for (double v : m.com) {
    cells.CommaDouble(v);
  }
  for (double v : m.com_velocity) {
    cells.CommaDouble(v);
  }
  for (double v : m.orientation) {
    cells.CommaDouble(v);
  }
  cells.CommaDouble(m.heading);
  cells.Flush();
  for (bool attached : m.lock_attached) out.append(attached ? ",1" : ",0");
  row->has_seq = true;
  row->seq = m.seq;
  return true;
}

std::vector<std::string> RobotStateFlattener::ColumnNames() const {
  const robot_state_t& m = msg_;
  std::vector<std::string> names = {"time", "seq", "robot", "sim_time"};
  const bool frames_per_module = m.num_frames == 2 * m.num_modules;
  const bool joint_per_module = m.num_joints == m.num_modules;
  auto joint_names = [&names](const std::string& prefix) {
    for (const char* n : {"angle", "speed", "torque"}) {
      names.push_back(prefix + "." + n);
    }
    PoseNames(prefix, &names);
  };
  for (int i = 0; i < m.num_modules; ++i) {
    const std::string mod = "module" + std::to_string(i);
    PoseNames(mod, &names);
    if (frames_per_module) {
      PoseNames(mod + ".frame0", &names);
      PoseNames(mod + ".frame1", &names);
    }
    if (joint_per_module) joint_names(mod + ".joint");
  }
  if (!frames_per_module) {
    for (int k = 0; k < m.num_frames; ++k) {
      PoseNames("frame" + std::to_string(k), &names);
    }
  }
  if (!joint_per_module) {
    for (int k = 0; k < m.num_joints; ++k) {
      joint_names("joint" + std::to_string(k));
    }
  }
  // Sensor values are named by their kind's table (sensor_kind.h).
  const SensorKind& force = *FindSensorKind("force");
  const SensorKind& distance = *FindSensorKind("distance");
  for (int k = 0; k < m.num_sensor_modules; ++k) {
    const std::string sm = "sensor_module" + std::to_string(k);
    const sensor_module_state_t& s = m.sensor_modules[k];
    PoseNames(sm, &names);
    if (s.has_force) {
      names.push_back(SensorValueName(sm, force, -1, force.channels[0]));
    }
    for (int j = 0; j < s.num_distances; ++j) {
      std::string name = SensorValueName(sm, distance, s.distance_face[j],
                                         distance.channels[0]);
      // Two sensors on one face keep distinct names.
      for (int i = 0; i < j; ++i) {
        if (s.distance_face[i] == s.distance_face[j]) {
          name += "_" + std::to_string(j);
          break;
        }
      }
      names.push_back(name);
    }
    for (int r = 0; r < s.num_readings; ++r) {
      const sensor_reading_t& reading = s.readings[r];
      const SensorKind* kind = FindSensorKind(reading.kind);
      for (int j = 0; j < reading.num_values; ++j) {
        if (kind != nullptr && j < static_cast<int>(kind->channels.size())) {
          names.push_back(
              SensorValueName(sm, *kind, reading.face, kind->channels[j]));
        } else {
          // A kind this build does not know (or more values than it
          // has): named by position, never by the sender's text.
          names.push_back(sm + ".reading" + std::to_string(r) + "." +
                          std::to_string(j));
        }
      }
    }
  }
  for (const char* n : {"com.x", "com.y", "com.z", "com_velocity.x",
                        "com_velocity.y", "com_velocity.z"}) {
    names.push_back(n);
  }
  // The robot's orientation (w, x, y, z as in every pose) and heading.
  for (const char* n : {"orientation.qw", "orientation.qx", "orientation.qy",
                        "orientation.qz", "heading"}) {
    names.push_back(n);
  }
  // Named by the lock (guid or robot/lockN) so a column keeps its meaning
  // across scenarios; 1 while the lock holds, 0 after DETACH or a break.
  for (const std::string& lock : m.lock_names) {
    names.push_back("lock." + lock + ".attached");
  }
  return names;
}

}  // namespace mrsim
