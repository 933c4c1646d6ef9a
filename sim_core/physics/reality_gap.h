// The reality gap: what a real robot and a real floor do that the nominal
// model does not. Per-step imperfections of sensors and servos (applied by
// Physics::SetRealityGap) and per-episode randomisation of the world
// (PerturbScenario), all drawn from one seed: the same seed gives the same
// episode bit for bit (docs/physics.md, "The reality gap"). The per-step
// part is the physics effect "reality_gap" (RealityGapEffect).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "sim_core/physics/physics_effect.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

struct RealityGap {
  // --- Per step (Physics). Noise is white, Gaussian, a pure function of
  // (seed, step, channel), so it needs no state and a checkpoint resumes it.
  double sensor_noise = 0;  // sd of force and distance readings, share of it
  double sensor_bias = 0;   // each force/distance sensor: x U(1-b, 1+b)
  double joint_noise = 0;   // rad, sd of joint angle readings
  double motor_noise = 0;   // rad/s, sd added to each servo's speed command
  double latency = 0;       // s, the servo acts on targets this old
  double backlash = 0;      // rad, dead band of the position loop
  double max_accel = 0;     // rad/s^2, speed command slew limit; 0 none
  // --- Per episode (PerturbScenario): each value x U(1-r, 1+r).
  double friction_range = 0;  // every ContactFriction coefficient
  double mass_range = 0;      // every frame, sensor module, plate, object
  double gain_range = 0;      // each hinge's Kp, velocityGain, maxTorque
  double terrain_range = 0;   // the height field's height
  uint64_t seed = 0;

  // The ranges `--robust` uses unless told otherwise (docs/optimizer.md):
  // what a hobby servo snake on a lab floor varies by.
  static RealityGap Typical();
  // Anything to do per step.
  bool any_per_step() const;
  // Throws std::invalid_argument naming the field and its bounds: every
  // value finite and >= 0, ranges < 1 (a factor stays positive), latency
  // <= 1 s, backlash <= 0.5 rad, noise within physical sizes.
  void Validate() const;
  // This gap with seed derived from (seed, index): the index-th episode.
  RealityGap ForEpisode(uint64_t index) const;
};

// The scenario with the per-episode randomisation drawn from gap.seed.
// Same gap, same scenario: the same result.
Scenario PerturbScenario(const Scenario& scenario, const RealityGap& gap);

// A standard normal number that depends only on its arguments.
double GapNormal(uint64_t seed, uint64_t step, uint64_t channel);

// Adds the gap's sensor noise and bias to a reading of robot `robot` taken
// at physics step `step`: joint angles (+ joint_noise N(0,1)), force and
// distance readings (x bias factor x (1 + sensor_noise N(0,1)), never
// negative, distances never beyond `max_distance` of their sensor).
void AddSensorNoise(const RealityGap& gap, uint64_t step, int robot,
                    const std::vector<std::vector<double>>& max_distance,
                    RobotState* state);

// The physics effect "reality_gap": the gap's per-step part. Takes the
// servo law (latency, backlash, motor noise, slew limit) and adds sensor
// noise to readings. Keeps the latency queue: the last latency / timestep
// + 1 target vectors per robot, a ring, restarted from the current targets
// when built and at Reset, carried when worlds merge, not checkpointed.
class RealityGapEffect : public PhysicsEffect {
 public:
  RealityGapEffect(const RealityGap& gap, const mjModel* m);
  // Its PhysicsEffectKinds() row: nullptr when the gap has nothing to do
  // per step (RealityGap::any_per_step).
  static std::unique_ptr<PhysicsEffect> Make(const PhysicsEffectInput& input);

  void Controls(const mjModel* m, const std::vector<const ServoRobot*>& robots,
                mjData* d, bool advance) override;
  void AdjustReadings(uint64_t step, uint64_t robot,
                      const std::vector<std::vector<double>>& max_distance,
                      RobotState* state) const override;
  void Restart(const std::vector<const ServoRobot*>& robots) override;
  void Absorb(const PhysicsEffect& from,
              const std::vector<int>& to_robot) override;

 private:
  RealityGap gap_;
  int latency_steps_ = 0;
  int ring_next_ = 0;
  std::vector<std::vector<std::vector<double>>> target_ring_;
};

}  // namespace mrsim
