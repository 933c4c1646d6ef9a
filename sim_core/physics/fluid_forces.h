// The physics effect "fluids": buoyancy and drag of water and air regions
// (Scenario::fluid_regions), applied through mjData::xfrc_applied before
// each step.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <vector>

#include "sim_core/physics/physics_effect.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Per geom of every moving body: the part of its volume inside a region
// (from its vertical extent) gets buoyancy density * V * g at the centre of
// the submerged slice, plus drag against the region's flow velocity,
// quadratic 0.5 rho Cd A |v| v with Cd = 1 and A = pi r^2 (r: radius of the
// sphere of equal volume) and linear (Stokes) 6 pi mu r v; rotation is
// damped likewise. Precomputes everything in the constructor;
// AddBodyForces allocates nothing.
class FluidForces : public PhysicsEffect {
 public:
  FluidForces(const mjModel* m, const std::vector<FluidRegion>& regions);
  // Its PhysicsEffectKinds() row: nullptr when the scenario has no region.
  static std::unique_ptr<PhysicsEffect> Make(const PhysicsEffectInput& input);

  bool empty() const { return regions_.empty(); }
  // Adds to `xfrc` (nbody x 6, usually d->xfrc_applied) the fluid forces
  // of the kinematics in d (after mj_step1 / mj_forward).
  void AddBodyForces(const mjModel* m, const mjData* d,
                     mjtNum* xfrc) const override;

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
