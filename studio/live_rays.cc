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

// A distance sensor's ray from its site along the site's x axis, as
// Physics casts it: skipping the sensor module's own body and its force
// plate (a child body), up to `length`.
Ray CastSiteRay(const mjModel* m, const mjData* d, int site, double length) {
  const int body = m->site_bodyid[site];
  mjtNum point[3], dir[3];
  mju_copy3(point, d->site_xpos + 3 * site);
  const mjtNum* x = d->site_xmat + 9 * site;
  dir[0] = x[0];
  dir[1] = x[3];
  dir[2] = x[6];
  Ray ray;
  ray.from = Eigen::Vector3d(point[0], point[1], point[2]);
  const Eigen::Vector3d along(dir[0], dir[1], dir[2]);
  double travelled = 0;
  for (int attempt = 0; attempt < 4 && travelled < length; ++attempt) {
    int geom = -1;
    const mjtNum dist = mj_ray(m, d, point, dir, nullptr, 1, body, &geom);
    if (dist < 0 || geom < 0 || travelled + dist > length) break;
    if (m->body_parentid[m->geom_bodyid[geom]] != body) {
      ray.hit = true;
      ray.to = ray.from + (travelled + dist) * along;
      return ray;
    }
    const double step = dist + 1e-6;  // through the plate
    travelled += step;
    for (int i = 0; i < 3; ++i) point[i] += step * dir[i];
  }
  ray.to = ray.from + length * along;
  return ray;
}

}  // namespace mrsim::studio
