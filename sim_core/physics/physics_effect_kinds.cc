#include "sim_core/physics/physics_effect_kinds.h"

#include <utility>

#include "sim_core/physics/directional_friction.h"
#include "sim_core/physics/fluid_forces.h"
#include "sim_core/physics/reality_gap.h"

namespace mrsim {

const std::vector<PhysicsEffectKind>& PhysicsEffectKinds() {
  static const std::vector<PhysicsEffectKind> kinds = {
      {"fluids",
       "buoyancy and drag of the scenario's water and air regions "
       "(`fluid_regions`)",
       kHookBodyForces, &FluidForces::Make},
      {"directional_friction",
       "contacts of a `directional` ContactFriction entry or of passive "
       "wheels turned to the part's axis, with forward, backward and lateral "
       "coefficients",
       kHookContacts, &DirectionalFriction::Make},
      {"reality_gap",
       "per-step servo latency, backlash, noise and slew limit, and sensor "
       "noise and bias (`Physics::SetRealityGap`)",
       kHookControls | kHookReadings, &RealityGapEffect::Make},
  };
  return kinds;
}

std::string PhysicsHookNames(unsigned hooks) {
  static const std::pair<PhysicsHook, const char*> kNames[] = {
      {kHookControls, "servo commands"},
      {kHookBodyForces, "body forces"},
      {kHookContacts, "contacts"},
      {kHookReadings, "readings"},
  };
  std::string out;
  for (const auto& [hook, name] : kNames) {
    if (!(hooks & hook)) continue;
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

}  // namespace mrsim
