// The studio's colours per kind of part, applied to the MuJoCo scene by
// geom (until the generated MJCF carries them itself, branch `physics`),
// with the selected part highlighted.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "studio/part_map.h"

namespace mrsim::studio {

// RGBA of a kind of part (also used for the palette's swatches).
const float* LookColor(Look look);

// Recolours the model's geoms in `scene` and lights up `selected`.
void ApplyLooks(const std::vector<GeomPart>& geoms, const Selection& selected,
                mjvScene* scene);

}  // namespace mrsim::studio
