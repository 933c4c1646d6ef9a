// The physics effect "directional_friction": orients each contact's friction by
// the frame of the part that touches (forward, backward and lateral
// coefficients, passive wheels). MuJoCo 2.2 makes every contact isotropic about
// its normal with an arbitrary tangent frame; between collision detection and
// constraint building this turns the first tangent onto the part's forward axis
// and sets the coefficients (docs/physics.md, "Directional friction").
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <vector>

#include "sim_core/physics/physics_effect.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

class DirectionalFriction : public PhysicsEffect {
 public:
  // Sliding friction along a passive wheel's rolling direction (both
  // ways): a small caster's rolling resistance.
  static constexpr double kWheelRolling = 0.02;

  // Reads which geoms of `model` (built from `scenario` by BuildMjcf) have
  // a directional ContactFriction entry or passive wheels.
  DirectionalFriction(const Scenario& scenario, const mjModel* model);
  // Its PhysicsEffectKinds() row: nullptr when it is empty().
  static std::unique_ptr<PhysicsEffect> Make(const PhysicsEffectInput& input);

  // No directional entry and no passive wheels: AdjustContacts would
  // change nothing (an entry whose materials no geom has still counts).
  bool empty() const { return empty_; }

  // Rewrites the frame, friction and dim of every contact in d->contact
  // that involves a directional part. Call after mj_collision and before
  // mj_makeConstraint; needs the kinematics of the state (mj_kinematics,
  // mj_comPos). Uses d's stack, allocates nothing.
  void AdjustContacts(const mjModel* m, mjData* d) const override;

 private:
  struct Rule {
    double forward = 0, backward = 0, lateral = 0, torsional = 0, rolling = 0;
    bool wheel = false;  // lateral and spin/rolling from the contact itself
  };
  // Per geom: its scenario material's index (-1: not colliding, unknown)
  // and whether it carries passive wheels.
  std::vector<int> geom_material_;
  std::vector<char> geom_wheel_;
  // Per pair of material indices (row = material of the oriented part):
  // index into rules_ or -1.
  std::vector<int> pair_rule_;
  int materials_ = 0;
  std::vector<Rule> rules_;
  bool empty_ = true;

  // The rule for a contact of geoms g1, g2 and which of them orients it
  // (0 or 1); nullptr when neither is directional.
  const Rule* Find(const mjModel* m, int g1, int g2, int* side) const;
};

}  // namespace mrsim
