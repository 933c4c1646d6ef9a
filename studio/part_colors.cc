#include "studio/part_colors.h"

namespace mrsim::studio {

const float* LookColor(Look look) {
  static const float kColors[][4] = {
      {0.60f, 0.60f, 0.60f, 1.0f},  // other
      {0.95f, 0.55f, 0.15f, 1.0f},  // pitch module: orange
      {0.20f, 0.50f, 0.95f, 1.0f},  // yaw module: blue
      {0.25f, 0.72f, 0.45f, 1.0f},  // sensor module: green
      {0.85f, 0.20f, 0.35f, 1.0f},  // force plate: red
      {1.00f, 0.85f, 0.10f, 1.0f},  // distance sensor: yellow
      {0.62f, 0.40f, 0.85f, 1.0f},  // object: purple
      {0.42f, 0.46f, 0.50f, 1.0f},  // terrain: grey
  };
  return kColors[static_cast<int>(look)];
}

void ApplyLooks(const std::vector<GeomPart>& geoms, const Selection& selected,
                mjvScene* scene) {
  for (int i = 0; i < scene->ngeom; ++i) {
    mjvGeom& g = scene->geoms[i];
    if (g.objtype != mjOBJ_GEOM || g.objid < 0 ||
        g.objid >= static_cast<int>(geoms.size())) {
      continue;
    }
    const GeomPart& part = geoms[g.objid];
    if (part.look == Look::kOther) continue;
    const float* c = LookColor(part.look);
    for (int k = 0; k < 4; ++k) g.rgba[k] = c[k];
    if (part.part.kind != PartKind::kNone && part.part == selected) {
      g.emission = 0.6f;
    }
  }
}

}  // namespace mrsim::studio
