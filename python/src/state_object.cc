#include "python/src/state_object.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "logger/csv_columns.h"
#include "logger/lcm_type_registry.h"
#include "logger/robot_state_flattener.h"
#include "python/src/bindings.h"
#include "sim_core/codec/state_message.h"

namespace py = pybind11;

namespace mrsim::python {

robot_state_t StateObject::ToMessage() const {
  robot_state_t msg = ToRobotStateMessage(state, seq);
  SetLockStates(locks, &msg);
  return msg;
}

StateObject StateObject::FromMessage(const robot_state_t& msg) {
  StateObject s;
  s.state = FromRobotStateMessage(msg);
  s.seq = msg.seq;
  s.locks.reserve(msg.lock_names.size());
  for (size_t i = 0; i < msg.lock_names.size() && i < msg.lock_attached.size();
       ++i) {
    s.locks.emplace_back(msg.lock_names[i], msg.lock_attached[i]);
  }
  return s;
}

namespace {

using Array = py::array_t<double>;

// Pose rows as the logger writes them: x, y, z, qw, qx, qy, qz.
void PutPose(const Pose& p, double* row) {
  row[0] = p.position.x();
  row[1] = p.position.y();
  row[2] = p.position.z();
  row[3] = p.orientation.w();
  row[4] = p.orientation.x();
  row[5] = p.orientation.y();
  row[6] = p.orientation.z();
}

template <class T, class F>
Array Poses(const std::vector<T>& items, F pose_of) {
  Array a({static_cast<py::ssize_t>(items.size()), py::ssize_t{7}});
  double* d = a.mutable_data();
  for (size_t i = 0; i < items.size(); ++i)
    PutPose(pose_of(items[i]), d + 7 * i);
  return a;
}

template <class F>
Array Joints(const RobotState& s, F value_of) {
  Array a(static_cast<py::ssize_t>(s.joints.size()));
  double* d = a.mutable_data();
  for (size_t i = 0; i < s.joints.size(); ++i) d[i] = value_of(s.joints[i]);
  return a;
}

Array Vector3(const Eigen::Vector3d& v) {
  Array a(3);
  double* d = a.mutable_data();
  for (int i = 0; i < 3; ++i) d[i] = v[i];
  return a;
}

// w, x, y, z as the logger writes it.
Array Quaternion(const Eigen::Quaterniond& q) {
  Array a(4);
  double* d = a.mutable_data();
  d[0] = q.w();
  d[1] = q.x();
  d[2] = q.y();
  d[3] = q.z();
  return a;
}

Array SensorForces(const RobotState& s) {
  Array a(static_cast<py::ssize_t>(s.sensor_modules.size()));
  double* d = a.mutable_data();
  for (size_t i = 0; i < s.sensor_modules.size(); ++i) {
    d[i] = s.sensor_modules[i].has_force
               ? s.sensor_modules[i].force
               : std::numeric_limits<double>::quiet_NaN();
  }
  return a;
}

// Three values of each sensor module's first reading of `kind` from
// `first` on (the IMU's accel at 0, gyro at 3), shape (sensor_modules, 3);
// NaN rows where a module has no such reading.
Array ReadingTriples(const RobotState& s, const std::string& kind,
                     size_t first) {
  Array a({static_cast<py::ssize_t>(s.sensor_modules.size()),
           static_cast<py::ssize_t>(3)});
  double* d = a.mutable_data();
  for (size_t i = 0; i < s.sensor_modules.size(); ++i) {
    const SensorReading* found = nullptr;
    for (const SensorReading& r : s.sensor_modules[i].readings) {
      if (r.kind == kind && r.values.size() >= first + 3) {
        found = &r;
        break;
      }
    }
    for (size_t j = 0; j < 3; ++j) {
      d[3 * i + j] = found != nullptr
                         ? found->values[first + j]
                         : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return a;
}

// Every reading carried in SensorModuleState::readings (the IMU and any
// kind after it), per sensor module: {kind: array (instances, values)}.
py::list SensorReadings(const RobotState& s) {
  py::list out;
  for (const SensorModuleState& m : s.sensor_modules) {
    std::map<std::string, std::vector<const SensorReading*>> by_kind;
    for (const SensorReading& r : m.readings) by_kind[r.kind].push_back(&r);
    py::dict kinds;
    for (const auto& [kind, readings] : by_kind) {
      size_t width = 0;
      for (const SensorReading* r : readings) {
        width = std::max(width, r->values.size());
      }
      Array a({static_cast<py::ssize_t>(readings.size()),
               static_cast<py::ssize_t>(width)});
      double* d = a.mutable_data();
      for (size_t k = 0; k < readings.size(); ++k) {
        for (size_t j = 0; j < width; ++j) {
          d[k * width + j] = j < readings[k]->values.size()
                                 ? readings[k]->values[j]
                                 : std::numeric_limits<double>::quiet_NaN();
        }
      }
      kinds[py::str(kind)] = a;
    }
    out.append(kinds);
  }
  return out;
}

// The logger's CSV row of this state: the same flattener mrsim-log uses,
// so names and values are those of its files.
py::dict Columns(const StateObject& s) {
  static const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  robot_state_t msg = s.ToMessage();
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  FlatRow row;
  if (!flattener.Flatten(bytes.data(), bytes.size(), &row)) {
    throw std::runtime_error("state: the logger could not flatten it");
  }
  const std::vector<std::string> cells = SplitCsvRecord(row.values);
  const std::vector<std::string>& names = flattener.columns();
  py::dict out;
  for (size_t i = 0; i < names.size() && i < cells.size(); ++i) {
    if (names[i] == "robot") {
      out[py::str(names[i])] = cells[i];
      continue;
    }
    double v = std::numeric_limits<double>::quiet_NaN();
    const std::string& c = cells[i];
    std::from_chars(c.data(), c.data() + c.size(), v);
    if (names[i] == "seq") {
      out[py::str(names[i])] = static_cast<int64_t>(v);
    } else {
      out[py::str(names[i])] = v;
    }
  }
  return out;
}

}  // namespace

void BindState(py::module_& m) {
  py::class_<StateObject, std::shared_ptr<StateObject>> c(m, "State", R"doc(
One robot's state at one simulation time, as mrsim-sim publishes it on
MRSIM_STATE_<robot>. Arrays are numpy float64; poses are rows
(x, y, z, qw, qx, qy, qz) in the world frame (Z up, m), the order of the
logger's CSV columns. columns() gives the logger's CSV row itself.)doc");
  c.def_property_readonly(
      "time", [](const StateObject& s) { return s.state.time; },
      "Simulation time (s).");
  c.def_property(
      "seq", [](const StateObject& s) { return s.seq; },
      [](StateObject& s, int64_t seq) { s.seq = seq; },
      "The state message's seq (-1 for a state read in process; set it to "
      "publish the state as a simulator would).");
  c.def_property_readonly(
      "robot", [](const StateObject& s) { return s.state.robot; },
      "Robot name.");
  c.def_property_readonly(
      "joint_angle",
      [](const StateObject& s) {
        return Joints(s.state, [](const JointState& j) { return j.angle; });
      },
      "Hinge angles (rad), chain order (CSV: module<i>.joint.angle).");
  c.def_property_readonly(
      "joint_speed",
      [](const StateObject& s) {
        return Joints(s.state, [](const JointState& j) { return j.speed; });
      },
      "Hinge speeds (rad/s) (CSV: module<i>.joint.speed).");
  c.def_property_readonly(
      "joint_torque",
      [](const StateObject& s) {
        return Joints(s.state, [](const JointState& j) { return j.torque; });
      },
      "Actuator torques (N m) (CSV: module<i>.joint.torque).");
  c.def_property_readonly(
      "joint_pose",
      [](const StateObject& s) {
        return Poses(s.state.joints, [](const JointState& j) -> const Pose& {
          return j.world;
        });
      },
      "Hinge world poses, shape (joints, 7) (CSV: module<i>.joint.x .. qz).");
  c.def_property_readonly(
      "module_pose",
      [](const StateObject& s) {
        return Poses(s.state.modules,
                     [](const Pose& p) -> const Pose& { return p; });
      },
      "Module centre poses, shape (modules, 7) (CSV: module<i>.x .. qz).");
  c.def_property_readonly(
      "frame_pose",
      [](const StateObject& s) {
        return Poses(s.state.frames,
                     [](const Pose& p) -> const Pose& { return p; });
      },
      "Frame poses, two per module (left, right), shape (2 * modules, 7) "
      "(CSV: module<i>.frame0.x .., module<i>.frame1.x ..).");
  c.def_property_readonly(
      "sensor_pose",
      [](const StateObject& s) {
        return Poses(
            s.state.sensor_modules,
            [](const SensorModuleState& m) -> const Pose& { return m.pose; });
      },
      "Sensor module poses, shape (sensor_modules, 7) (CSV: "
      "sensor_module<k>.x .. qz).");
  c.def_property_readonly(
      "sensor_force",
      [](const StateObject& s) { return SensorForces(s.state); },
      "Force sensor readings (N) per sensor module; NaN where a module has "
      "no force sensor (CSV: sensor_module<k>.force).");
  c.def_property_readonly(
      "sensor_distance",
      [](const StateObject& s) {
        py::list out;
        for (const SensorModuleState& m : s.state.sensor_modules) {
          out.append(
              py::array_t<double>(m.distances.size(), m.distances.data()));
        }
        return out;
      },
      "Distance readings (m) of each sensor module, one array per module "
      "(CSV: sensor_module<k>.distance<face>).");
  c.def_property_readonly(
      "sensor_distance_face",
      [](const StateObject& s) {
        py::list out;
        for (const SensorModuleState& m : s.state.sensor_modules) {
          out.append(py::cast(m.distance_faces));
        }
        return out;
      },
      "The face (0..5) of each distance sensor, per sensor module.");
  c.def_property_readonly(
      "imu_accel",
      [](const StateObject& s) { return ReadingTriples(s.state, "imu", 0); },
      "IMU accelerometer readings (m/s^2, the sensor module's axes; at rest "
      "+9.81 along its up), shape (sensor_modules, 3); NaN rows where a "
      "module has no IMU (CSV: sensor_module<k>.imu.accel.x .. z).");
  c.def_property_readonly(
      "imu_gyro",
      [](const StateObject& s) { return ReadingTriples(s.state, "imu", 3); },
      "IMU gyroscope readings (rad/s, the sensor module's axes), shape "
      "(sensor_modules, 3); NaN rows where a module has no IMU (CSV: "
      "sensor_module<k>.imu.gyro.x .. z).");
  c.def_property_readonly(
      "sensor_readings",
      [](const StateObject& s) { return SensorReadings(s.state); },
      "Readings of the sensor kinds that travel as readings (the IMU: "
      "accel.x, accel.y, accel.z, gyro.x, gyro.y, gyro.z), one dict per "
      "sensor module from kind name to an array of shape (instances, "
      "values).");
  c.def_property_readonly(
      "com", [](const StateObject& s) { return Vector3(s.state.com); },
      "Centre of mass (m) (CSV: com.x, com.y, com.z).");
  c.def_property_readonly(
      "com_velocity",
      [](const StateObject& s) { return Vector3(s.state.com_velocity); },
      "Centre-of-mass velocity (m/s) (CSV: com_velocity.x ..).");
  c.def_property_readonly(
      "orientation",
      [](const StateObject& s) { return Quaternion(s.state.orientation); },
      "The robot's orientation in the world, quaternion (w, x, y, z): its "
      "head frame's (module 0's front frame; docs/sim.md, \"The robot's "
      "orientation\"). At t=0 the head frame's quatRotation in the design "
      "(CSV: orientation.qw, orientation.qx ..).");
  c.def_property_readonly(
      "heading", [](const StateObject& s) { return s.state.heading; },
      "Yaw of the head frame's forward (+x) axis about world z (rad, "
      "-pi..pi: 0 facing +x, pi/2 facing +y) (CSV: heading).");
  c.def_property_readonly(
      "locks", [](const StateObject& s) { return s.locks; },
      "(name, attached) of every lock of the robot, scenario order (CSV: "
      "lock.<name>.attached).");
  c.def_property_readonly(
      "joint_axes",
      [](const StateObject& s) {
        std::vector<std::string> out;
        for (Axis a : s.axes)
          out.push_back(a == Axis::kPitch ? "pitch" : "yaw");
        return out;
      },
      "Hinge axes ('pitch'/'yaw') when known (states of a Simulation); "
      "empty for states received over LCM.");
  c.def(
      "arrays",
      [](const StateObject& s) {
        const RobotState& r = s.state;
        py::dict d;
        d["time"] = r.time;
        d["joint_angle"] =
            Joints(r, [](const JointState& j) { return j.angle; });
        d["joint_speed"] =
            Joints(r, [](const JointState& j) { return j.speed; });
        d["joint_torque"] =
            Joints(r, [](const JointState& j) { return j.torque; });
        d["joint_pose"] =
            Poses(r.joints,
                  [](const JointState& j) -> const Pose& { return j.world; });
        d["module_pose"] =
            Poses(r.modules, [](const Pose& p) -> const Pose& { return p; });
        d["frame_pose"] =
            Poses(r.frames, [](const Pose& p) -> const Pose& { return p; });
        d["sensor_pose"] = Poses(
            r.sensor_modules,
            [](const SensorModuleState& m) -> const Pose& { return m.pose; });
        d["sensor_force"] = SensorForces(r);
        d["imu_accel"] = ReadingTriples(r, "imu", 0);
        d["imu_gyro"] = ReadingTriples(r, "imu", 3);
        d["com"] = Vector3(r.com);
        d["com_velocity"] = Vector3(r.com_velocity);
        d["orientation"] = Quaternion(r.orientation);
        d["heading"] = r.heading;
        return d;
      },
      "Every array property above in one dict (what a policy or a log "
      "keeps).");
  c.def("columns", &Columns, R"doc(
The state as the logger's CSV row: a dict from column name ('time', 'seq',
'robot', 'sim_time', 'module3.x', 'module3.joint.angle',
'sensor_module0.force', 'com.x', 'lock.<name>.attached', ...) to value, in
the order of mrsim-log's columns; made by the logger's own flattener.)doc");
  c.def("__repr__", [](const StateObject& s) {
    return "<mrsim.State " + s.state.robot +
           " t=" + std::to_string(s.state.time) + " s, " +
           std::to_string(s.state.joints.size()) + " joints>";
  });
}

}  // namespace mrsim::python
