// The physics effects, listed once: what Physics adds to MuJoCo's model
// (fluids, directional friction, the reality gap, ...). Physics builds its
// effects from this list (physics_effects.h) and docs/physics.md's table of
// effects is checked against it (PhysicsEffectKinds.DocsListEveryEffect...).
// A new effect is one class implementing PhysicsEffect in its own file pair
// and one row here (docs/architecture.md, "Adding a physics effect").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim_core/physics/physics_effect.h"

namespace mrsim {

struct PhysicsEffectKind {
  // The word for it, in Physics::effects() and the docs: "fluids".
  const char* name;
  // One line for people: docs/physics.md, "Physics effects".
  const char* summary;
  // The PhysicsHook bits it takes part in.
  unsigned hooks;
  // The effect for this scenario, model and reality gap, or nullptr when
  // it has nothing to do there (then it costs nothing at all).
  std::unique_ptr<PhysicsEffect> (*make)(const PhysicsEffectInput& input);
};

// Every effect, in the order Physics calls them at a shared hook.
const std::vector<PhysicsEffectKind>& PhysicsEffectKinds();

// The hooks of `hooks` in words, in step order: "body forces, contacts".
std::string PhysicsHookNames(unsigned hooks);

}  // namespace mrsim
