// The physics effects one Physics runs: those of PhysicsEffectKinds() that
// have something to do for its scenario, model and reality gap, sorted by
// the hooks they take part in, so each hook of a step is one test of an
// empty list when no effect uses it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim_core/physics/physics_effect.h"

namespace mrsim {

class PhysicsEffects {
 public:
  // None: the model as MuJoCo steps it.
  PhysicsEffects() = default;
  // Makes every row of PhysicsEffectKinds() whose effect has work here.
  explicit PhysicsEffects(const PhysicsEffectInput& input);

  // The body-force effects, contact effects and reading effects in table
  // order, and the one effect that computes the servos' commands (nullptr:
  // the nominal servo law).
  const std::vector<const PhysicsEffect*>& body_forces() const {
    return body_forces_;
  }
  const std::vector<const PhysicsEffect*>& contacts() const {
    return contacts_;
  }
  const std::vector<const PhysicsEffect*>& readings() const {
    return readings_;
  }
  PhysicsEffect* controls() const { return controls_; }

  // The names of the effects built, in table order.
  std::vector<std::string> names() const;

  // PhysicsEffect::Restart of every effect.
  void Restart(const std::vector<const ServoRobot*>& robots);
  // PhysicsEffect::Absorb of every effect built here and in `from`.
  void Absorb(const PhysicsEffects& from, const std::vector<int>& to_robot);

 private:
  struct Built {
    size_t kind = 0;  // its row in PhysicsEffectKinds()
    std::unique_ptr<PhysicsEffect> effect;
  };
  std::vector<Built> built_;
  std::vector<const PhysicsEffect*> body_forces_, contacts_, readings_;
  PhysicsEffect* controls_ = nullptr;
};

}  // namespace mrsim
