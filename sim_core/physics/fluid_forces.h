// Buoyancy and drag of water and air regions (Scenario::fluid_regions),
// applied through mjData::xfrc_applied before each step.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Per geom of every moving body: the part of its volume inside a region
// (from its vertical extent) gets buoyancy density * V * g at the centre of
// the submerged slice, plus drag against the region's flow velocity,
// quadratic 0.5 rho Cd A |v| v with Cd = 1 and A = pi r^2 (r: radius of the
// sphere of equal volume) and linear (Stokes) 6 pi mu r v; rotation is
// damped likewise. Precomputes everything in the constructor; Apply()
// allocates nothing.
class FluidForces {
 public:
  FluidForces(const mjModel* m, const std::vector<FluidRegion>& regions);

  bool empty() const { return regions_.empty(); }
  // Overwrites `xfrc` (nbody x 6, usually d->xfrc_applied) with the fluid
  // forces of the kinematics in d (after mj_step1 / mj_forward).
  void Apply(const mjModel* m, const mjData* d, mjtNum* xfrc) const;

 private:
  struct Geom {
    int id = 0;
    int body = 0;
    double volume = 0;
    double radius = 0;  // of the sphere with the same volume
  };
  std::vector<FluidRegion> regions_;
  std::vector<Geom> geoms_;
};

}  // namespace mrsim
