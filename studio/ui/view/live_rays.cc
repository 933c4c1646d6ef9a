#include "studio/ui/view/live_rays.h"

#include <algorithm>

#include "sim_core/physics/distance_ray.h"

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

Ray CastSiteRay(const mjModel* m, const mjData* d, int site, double length) {
  // The sensor module's force plate is its child body (sim_core's MJCF).
  const int body = m->site_bodyid[site];
  int plate = -1;
  for (int b = 1; b < m->nbody && plate < 0; ++b) {
    if (m->body_parentid[b] == body) plate = b;
  }
  const DistanceRay cast = CastDistanceRay(m, d, site, plate, length);
  const mjtNum* p = d->site_xpos + 3 * site;
  const mjtNum* x = d->site_xmat + 9 * site;
  Ray ray;
  ray.from = Eigen::Vector3d(p[0], p[1], p[2]);
  ray.to = ray.from + cast.distance * Eigen::Vector3d(x[0], x[3], x[6]);
  ray.hit = cast.hit;
  return ray;
}

}  // namespace mrsim::studio
