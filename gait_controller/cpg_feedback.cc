#include "gait_controller/cpg_feedback.h"

#include <algorithm>
#include <limits>

namespace mrsim {

std::vector<double> CpgFeedback(const RobotState& state,
                                const CpgParameters& p) {
  std::vector<double> inputs(state.joints.size(), 0.0);
  if (inputs.empty()) return inputs;
  for (const SensorModuleState& m : state.sensor_modules) {
    double s = 0;
    if (m.has_force && p.force_scale > 0) {
      s = std::max(s, std::min(1.0, m.force / p.force_scale));
    }
    for (double d : m.distances) {
      if (p.distance_range > 0) {
        s = std::max(s, std::max(0.0, 1.0 - d / p.distance_range));
      }
    }
    size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < state.joints.size(); ++j) {
      const double d =
          (state.joints[j].world.position - m.pose.position).squaredNorm();
      if (d < best) {
        best = d;
        nearest = j;
      }
    }
    inputs[nearest] = std::max(inputs[nearest], std::clamp(s, 0.0, 1.0));
  }
  return inputs;
}

}  // namespace mrsim
