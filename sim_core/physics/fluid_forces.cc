#include "sim_core/physics/fluid_forces.h"

#include <algorithm>
#include <cmath>

#include "sim_core/mjcf/mjcf_builder.h"

namespace mrsim {
namespace {

constexpr double kDragCoefficient = 1.0;

double GeomVolume(const mjModel* m, int g) {
  const mjtNum* s = m->geom_size + 3 * g;
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      return 4.0 / 3.0 * M_PI * s[0] * s[0] * s[0];
    case mjGEOM_CAPSULE:
      return M_PI * s[0] * s[0] * 2 * s[1] +
             4.0 / 3.0 * M_PI * std::pow(s[0], 3);
    case mjGEOM_CYLINDER:
      return M_PI * s[0] * s[0] * 2 * s[1];
    case mjGEOM_ELLIPSOID:
      return 4.0 / 3.0 * M_PI * s[0] * s[1] * s[2];
    default:  // box; a mesh uses its equivalent-inertia box
      return 8 * s[0] * s[1] * s[2];
  }
}

// Half of the geom's extent along world z.
double VerticalHalfExtent(const mjModel* m, const mjData* d, int g) {
  const mjtNum* s = m->geom_size + 3 * g;
  const mjtNum* r = d->geom_xmat + 9 * g + 6;  // third row: z of each axis
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      return s[0];
    case mjGEOM_CAPSULE:
      return std::abs(r[2]) * s[1] + s[0];
    case mjGEOM_CYLINDER:
      return std::abs(r[2]) * s[1] +
             s[0] * std::sqrt(std::max(0.0, 1 - r[2] * r[2]));
    case mjGEOM_ELLIPSOID:
      return std::sqrt(r[0] * r[0] * s[0] * s[0] + r[1] * r[1] * s[1] * s[1] +
                       r[2] * r[2] * s[2] * s[2]);
    default:
      return std::abs(r[0]) * s[0] + std::abs(r[1]) * s[1] +
             std::abs(r[2]) * s[2];
  }
}

}  // namespace

FluidForces::FluidForces(const mjModel* m,
                         const std::vector<FluidRegion>& regions)
    : regions_(regions) {
  if (regions_.empty()) return;
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = m->geom_bodyid[g];
    if (b == 0 || m->body_weldid[b] == 0) continue;  // fixed to the world
    if (m->geom_type[g] == mjGEOM_PLANE || m->geom_type[g] == mjGEOM_HFIELD) {
      continue;
    }
    // The frames it stands in for feel the water.
    if (m->geom_group[g] == kMjcfContactGroup) continue;
    Geom geom;
    geom.id = g;
    geom.body = b;
    geom.volume = GeomVolume(m, g);
    geom.radius = std::cbrt(3 * geom.volume / (4 * M_PI));
    geoms_.push_back(geom);
  }
}

std::unique_ptr<PhysicsEffect> FluidForces::Make(
    const PhysicsEffectInput& input) {
  if (input.scenario.fluid_regions.empty()) return nullptr;
  return std::make_unique<FluidForces>(input.model,
                                       input.scenario.fluid_regions);
}

void FluidForces::AddBodyForces(const mjModel* m, const mjData* d,
                                mjtNum* xfrc) const {
  const mjtNum* gravity = m->opt.gravity;
  for (const FluidRegion& region : regions_) {
    const Eigen::Vector3d lo = region.position - region.size / 2;
    const Eigen::Vector3d hi = region.position + region.size / 2;
    for (const Geom& geom : geoms_) {
      const mjtNum* c = d->geom_xpos + 3 * geom.id;
      if (c[0] < lo.x() || c[0] > hi.x() || c[1] < lo.y() || c[1] > hi.y()) {
        continue;
      }
      const double hz = VerticalHalfExtent(m, d, geom.id);
      const double bottom = std::max(c[2] - hz, lo.z());
      const double top = std::min(c[2] + hz, hi.z());
      if (top <= bottom) continue;
      const double fraction =
          hz > 0 ? std::min(1.0, (top - bottom) / (2 * hz)) : 1.0;
      const double rho = region.density;
      // Buoyancy at the centre of the submerged slice.
      const double displaced = rho * geom.volume * fraction;
      mjtNum force[3] = {-displaced * gravity[0], -displaced * gravity[1],
                         -displaced * gravity[2]};
      const mjtNum point[3] = {c[0], c[1], (top + bottom) / 2};
      // Drag against the flow.
      mjtNum vel[6];
      mj_objectVelocity(m, d, mjOBJ_GEOM, geom.id, vel, 0);
      const double r = geom.radius;
      const double area = M_PI * r * r;
      mjtNum rel[3];
      for (int i = 0; i < 3; ++i) rel[i] = vel[3 + i] - region.velocity[i];
      const double speed = mju_norm3(rel);
      const double k_lin =
          fraction * (0.5 * rho * kDragCoefficient * area * speed +
                      6 * M_PI * region.viscosity * r);
      for (int i = 0; i < 3; ++i) force[i] -= k_lin * rel[i];
      const double spin = mju_norm3(vel);
      const double k_rot =
          fraction * (rho * kDragCoefficient * std::pow(r, 5) * spin +
                      8 * M_PI * region.viscosity * r * r * r);
      mjtNum* out = xfrc + 6 * geom.body;
      const mjtNum* com = d->xipos + 3 * geom.body;
      const mjtNum arm[3] = {point[0] - com[0], point[1] - com[1],
                             point[2] - com[2]};
      mjtNum torque[3];
      mju_cross(torque, arm, force);
      for (int i = 0; i < 3; ++i) {
        out[i] += force[i];
        out[3 + i] += torque[i] - k_rot * vel[i];
      }
    }
  }
}

}  // namespace mrsim
