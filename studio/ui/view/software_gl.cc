#include "studio/ui/view/software_gl.h"

#include <GL/gl.h>

#include <cstring>

namespace mrsim::studio {

bool IsSoftwareGl() {
  const char* renderer =
      reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return renderer != nullptr && (std::strstr(renderer, "llvmpipe") != nullptr ||
                                 std::strstr(renderer, "softpipe") != nullptr);
}

void CoarsenInfinitePlanes(const mjModel* m, const mjrContext& context,
                           mjvScene* scene) {
  const double zfar = m->vis.map.zfar * m->stat.extent;
  for (int i = 0; i < scene->ngeom; ++i) {
    mjvGeom& g = scene->geoms[i];
    if (g.type != mjGEOM_PLANE || g.dataid < 0 || g.size[0] > 0 ||
        g.size[1] > 0) {
      continue;
    }
    // The texture keeps its repeat per metre only when it is uniform (the
    // default plane is drawn scaled, the grid in metres).
    const bool textured = g.texid >= 0 && g.texid < context.ntexture;
    if (textured && !g.texuniform) continue;
    for (int k = 0; k < 2; ++k) {
      // As large as MuJoCo's grid for this plane (mjr_makeContext).
      const double cell = g.texrepeat[k] > 0
                              ? 2.0 / g.texrepeat[k]
                              : 2.1 * zfar / (mjMAXPLANEGRID - 2);
      g.size[k] = static_cast<float>((2.1 * zfar + 2 * cell) / 2);
    }
    g.dataid = -1;  // the context's default plane: numquads x numquads
  }
}

}  // namespace mrsim::studio
