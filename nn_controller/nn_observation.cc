#include "nn_controller/nn_observation.h"

namespace mrsim {

void ObservationOf(const RobotState& state, NnObservation* out) {
  out->time = state.time;
  const size_t n = state.joints.size();
  out->angles.resize(n);
  out->speeds.resize(n);
  for (size_t j = 0; j < n; ++j) {
    out->angles[j] = state.joints[j].angle;
    out->speeds[j] = state.joints[j].speed;
  }
  const Eigen::Quaterniond& q = state.orientation;
  out->orientation[0] = q.w();
  out->orientation[1] = q.x();
  out->orientation[2] = q.y();
  out->orientation[3] = q.z();
  for (int i = 0; i < 3; ++i) out->com_velocity[i] = state.com_velocity[i];
  out->sensor_values.clear();
  for (const SensorModuleState& m : state.sensor_modules) {
    if (m.has_force) out->sensor_values.push_back(m.force);
    for (double d : m.distances) out->sensor_values.push_back(d);
  }
}

}  // namespace mrsim
