#include "sim_core/physics/distance_ray.h"

#include <algorithm>

namespace mrsim {

DistanceRay CastDistanceRay(const mjModel* m, const mjData* d, int site,
                            int plate_body, double range) {
  const int body = m->site_bodyid[site];
  mjtNum point[3], dir[3];
  mju_copy3(point, d->site_xpos + 3 * site);
  const mjtNum* x = d->site_xmat + 9 * site;
  dir[0] = x[0];  // the site's x axis is the ray
  dir[1] = x[3];
  dir[2] = x[6];
  DistanceRay ray;
  ray.distance = range;
  double travelled = 0;
  // mj_ray skips one body (the module's own); the plate, a body of its
  // own, is stepped through.
  for (int attempt = 0; attempt < 4; ++attempt) {
    int geom = -1;
    const mjtNum dist = mj_ray(m, d, point, dir, nullptr, 1, body, &geom);
    if (dist < 0 || geom < 0) break;
    if (m->geom_bodyid[geom] != plate_body) {
      ray.distance = std::min(range, travelled + dist);
      ray.hit = travelled + dist < range;
      break;
    }
    const double step = dist + 1e-6;
    travelled += step;
    for (int i = 0; i < 3; ++i) point[i] += step * dir[i];
    if (travelled >= range) break;
  }
  return ray;
}

}  // namespace mrsim
