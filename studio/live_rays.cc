#include "studio/live_rays.h"

#include <algorithm>

namespace mrsim::studio {

std::vector<Ray> MeasuredRays(const StatePoseMapper& mapper,
                              const std::vector<const RobotState*>& states,
                              const mjData* data) {
  std::vector<Ray> rays;
  const int n = std::min(mapper.robot_count(), static_cast<int>(states.size()));
  for (int r = 0; r < n; ++r) {
    if (states[r] == nullptr) continue;
    const std::vector<Ray> robot = mapper.Rays(r, *states[r], data);
    rays.insert(rays.end(), robot.begin(), robot.end());
  }
  return rays;
}

}  // namespace mrsim::studio
