#include "lua_controller/lua_robot_state_fill.h"

#include <cmath>

#include "sim_core/scenario/sensor_kind.h"

namespace mrsim {

void FillLuaRobotState(const RobotState& state, LuaRobotState* out) {
  const size_t n = state.joints.size();
  out->angles.resize(n);
  out->speeds.resize(n);
  out->torques.resize(n);
  for (size_t j = 0; j < n; ++j) {
    out->angles[j] = state.joints[j].angle;
    out->speeds[j] = state.joints[j].speed;
    out->torques[j] = state.joints[j].torque;
  }
  for (int i = 0; i < 3; ++i) {
    out->com[i] = state.com[i];
    out->com_velocity[i] = state.com_velocity[i];
  }
  // w, x, y, z: MuJoCo's order, as robot_state_t carries it.
  out->orientation[0] = state.orientation.w();
  out->orientation[1] = state.orientation.x();
  out->orientation[2] = state.orientation.y();
  out->orientation[3] = state.orientation.z();
  out->heading = state.heading;
  // The kinds the message carries in fields of their own (sensor_kind.h).
  static const std::string force_kind = FindSensorKind("force")->name;
  static const std::string distance_kind = FindSensorKind("distance")->name;
  out->sensors.resize(state.sensor_modules.size());
  for (size_t k = 0; k < state.sensor_modules.size(); ++k) {
    const SensorModuleState& m = state.sensor_modules[k];
    LuaRobotState::Sensor& s = out->sensors[k];
    s.has_force = m.has_force && std::isfinite(m.force);
    s.force = s.has_force ? m.force : 0.0;
    s.distances.clear();
    for (double d : m.distances) {
      if (std::isfinite(d)) s.distances.push_back(d);
    }
    // Every reading under its kind's name: force and distance first, then
    // the other kinds.
    s.readings.clear();
    if (m.has_force) s.readings.push_back({force_kind, -1, {m.force}});
    for (size_t j = 0; j < m.distances.size(); ++j) {
      const int face = j < m.distance_faces.size() ? m.distance_faces[j] : -1;
      s.readings.push_back({distance_kind, face, {m.distances[j]}});
    }
    for (const SensorReading& r : m.readings) {
      s.readings.push_back({r.kind, r.face, r.values});
    }
  }
}

}  // namespace mrsim
