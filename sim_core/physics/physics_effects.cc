#include "sim_core/physics/physics_effects.h"

#include <stdexcept>
#include <utility>

#include "sim_core/physics/physics_effect_kinds.h"

namespace mrsim {

PhysicsEffects::PhysicsEffects(const PhysicsEffectInput& input) {
  const std::vector<PhysicsEffectKind>& kinds = PhysicsEffectKinds();
  for (size_t k = 0; k < kinds.size(); ++k) {
    std::unique_ptr<PhysicsEffect> effect = kinds[k].make(input);
    if (!effect) continue;
    PhysicsEffect* e = effect.get();
    const unsigned hooks = kinds[k].hooks;
    if (hooks & kHookBodyForces) body_forces_.push_back(e);
    if (hooks & kHookContacts) contacts_.push_back(e);
    if (hooks & kHookReadings) readings_.push_back(e);
    if (hooks & kHookControls) {
      if (controls_) {
        // One servo law at a time: the table must not list two.
        throw std::logic_error(std::string("physics effects: ") +
                               kinds[k].name +
                               " computes the servo commands, as an earlier "
                               "row does");
      }
      controls_ = e;
    }
    built_.push_back({k, std::move(effect)});
  }
}

std::vector<std::string> PhysicsEffects::names() const {
  std::vector<std::string> out;
  for (const Built& b : built_)
    out.push_back(PhysicsEffectKinds()[b.kind].name);
  return out;
}

void PhysicsEffects::Restart(const std::vector<const ServoRobot*>& robots) {
  for (Built& b : built_) b.effect->Restart(robots);
}

void PhysicsEffects::Absorb(const PhysicsEffects& from,
                            const std::vector<int>& to_robot) {
  for (Built& b : built_) {
    for (const Built& f : from.built_) {
      if (f.kind == b.kind) b.effect->Absorb(*f.effect, to_robot);
    }
  }
}

}  // namespace mrsim
