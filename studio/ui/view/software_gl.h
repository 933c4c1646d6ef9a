// Drawing the studio fast on software OpenGL (Mesa llvmpipe, no GPU),
// where every pixel and vertex costs CPU: what the studio changes in
// MuJoCo's rendering there that keep the picture (the same pixels, or
// differences of one level in a few); callers apply them only when
// IsSoftwareGl(), so on a GPU nothing changes. (Besides these the
// preview draws no shadows and no multisampling there, and no floor
// reflection while a part is dragged: preview.cc, docs/studio.md.)
#pragma once

#include <mujoco/mujoco.h>

namespace mrsim::studio {

// True when the current OpenGL context renders in software (llvmpipe,
// softpipe). Needs a current context.
bool IsSoftwareGl();

// Infinite ground planes as one large plane of 4 x 4 quads instead of
// MuJoCo's 200 x 200 grid (80,000 triangles lit per vertex every frame,
// twice with the reflection): the lights are directional, so the lighting
// of a flat plane does not depend on the grid, and the texture keeps its
// world-space repeat. Call after mjv_updateScene, before mjr_render.
void CoarsenInfinitePlanes(const mjModel* m, const mjrContext& context,
                           mjvScene* scene);

}  // namespace mrsim::studio
