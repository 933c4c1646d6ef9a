// How far a distance sensor sees: the one cast the simulator's readings
// and the studio's drawn rays share.
#pragma once

#include <mujoco/mujoco.h>

namespace mrsim {

struct DistanceRay {
  double distance = 0;  // to the first hit, or the range
  bool hit = false;     // false: nothing within range
};

// From the sensor's `site` (after mj_kinematics) along the site's x axis,
// skipping the sensor module's own body and its force plate (`plate_body`,
// -1 for none), up to `range`.
DistanceRay CastDistanceRay(const mjModel* m, const mjData* d, int site,
                            int plate_body, double range);

}  // namespace mrsim
