#include "sim_core/physics/reality_gap.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim_core/scenario/reality_gap_limits.h"

namespace mrsim {
namespace {

uint64_t SplitMix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform in (0, 1), 53 bits.
double Unit(uint64_t bits) { return ((bits >> 11) + 0.5) * 0x1.0p-53; }

// Draws factors U(1-r, 1+r) in a fixed order from one seed.
class Factors {
 public:
  explicit Factors(uint64_t seed) : state_(SplitMix(seed ^ 0x5EEDull)) {}
  double operator()(double range) {
    state_ = SplitMix(state_);
    return 1.0 + range * (2.0 * Unit(state_) - 1.0);
  }

 private:
  uint64_t state_;
};

void Check(const char* name, double value, double max) {
  if (!std::isfinite(value) || value < 0 || value > max) {
    throw std::invalid_argument(fmt::format(
        "reality gap: {} must be between 0 and {}, got {}", name, max, value));
  }
}

}  // namespace

RealityGap RealityGap::Typical() {
  RealityGap g;
  g.sensor_noise = kGapTypicalSensorNoise;
  g.sensor_bias = kGapTypicalSensorBias;
  g.joint_noise = kGapTypicalJointNoise;
  g.motor_noise = kGapTypicalMotorNoise;
  g.latency = kGapTypicalLatency;
  g.backlash = kGapTypicalBacklash;
  g.max_accel = kGapTypicalMaxAccel;
  g.friction_range = kGapTypicalFrictionRange;
  g.mass_range = kGapTypicalMassRange;
  g.gain_range = kGapTypicalGainRange;
  g.terrain_range = kGapTypicalTerrainRange;
  return g;
}

bool RealityGap::any_per_step() const {
  return sensor_noise > 0 || sensor_bias > 0 || joint_noise > 0 ||
         motor_noise > 0 || latency > 0 || backlash > 0 || max_accel > 0;
}

void RealityGap::Validate() const {
  Check("sensor_noise", sensor_noise, kGapMaxSensorNoise);
  Check("sensor_bias", sensor_bias, kGapMaxSensorBias);
  Check("joint_noise (rad)", joint_noise, kGapMaxJointNoise);
  Check("motor_noise (rad/s)", motor_noise, kGapMaxMotorNoise);
  Check("latency (s)", latency, kGapMaxLatency);
  Check("backlash (rad)", backlash, kGapMaxBacklash);
  Check("max_accel (rad/s^2)", max_accel, kGapMaxMaxAccel);
  Check("friction_range", friction_range, kGapMaxRange);
  Check("mass_range", mass_range, kGapMaxRange);
  Check("gain_range", gain_range, kGapMaxRange);
  Check("terrain_range", terrain_range, kGapMaxRange);
}

RealityGap RealityGap::ForEpisode(uint64_t index) const {
  RealityGap g = *this;
  g.seed = SplitMix(seed ^ SplitMix(index + 1));
  return g;
}

double GapNormal(uint64_t seed, uint64_t step, uint64_t channel) {
  const uint64_t a = SplitMix(seed ^ SplitMix(step ^ SplitMix(channel)));
  const uint64_t b = SplitMix(a);
  // Box-Muller.
  return std::sqrt(-2.0 * std::log(Unit(a))) * std::cos(2 * M_PI * Unit(b));
}

void AddSensorNoise(const RealityGap& gap, uint64_t step, int robot,
                    const std::vector<std::vector<double>>& max_distance,
                    RobotState* state) {
  // Channels: robot, kind (0 joint, 1 force, 2 distance), index; the bias
  // of a channel is its noise at a step no run reaches.
  constexpr uint64_t kBiasStep = ~0ull;
  auto channel = [robot](uint64_t kind, uint64_t index) {
    return (static_cast<uint64_t>(robot) << 40) | (kind << 32) | index;
  };
  auto bias = [&](uint64_t ch) {
    return 1.0 +
           gap.sensor_bias * std::tanh(GapNormal(gap.seed, kBiasStep, ch));
  };
  auto reading = [&](double value, uint64_t ch) {
    return std::max(
        0.0, value * bias(ch) *
                 (1.0 + gap.sensor_noise * GapNormal(gap.seed, step, ch)));
  };
  for (size_t j = 0; j < state->joints.size(); ++j) {
    state->joints[j].angle +=
        gap.joint_noise * GapNormal(gap.seed, step, channel(0, j));
  }
  for (size_t k = 0; k < state->sensor_modules.size(); ++k) {
    SensorModuleState& sm = state->sensor_modules[k];
    if (sm.has_force) sm.force = reading(sm.force, channel(1, k));
    for (size_t d = 0; d < sm.distances.size(); ++d) {
      double v = reading(sm.distances[d], channel(2, (k << 8) | d));
      if (k < max_distance.size() && d < max_distance[k].size()) {
        v = std::min(v, max_distance[k][d]);
      }
      sm.distances[d] = v;
    }
  }
}

RealityGapEffect::RealityGapEffect(const RealityGap& gap, const mjModel* m)
    : gap_(gap),
      latency_steps_(
          static_cast<int>(std::llround(gap.latency / m->opt.timestep))) {}

std::unique_ptr<PhysicsEffect> RealityGapEffect::Make(
    const PhysicsEffectInput& input) {
  if (!input.gap.any_per_step()) return nullptr;
  return std::make_unique<RealityGapEffect>(input.gap, input.model);
}

void RealityGapEffect::Controls(const mjModel* m,
                                const std::vector<const ServoRobot*>& robots,
                                mjData* d, bool advance) {
  if (!advance) return;  // d->ctrl holds the commands of the last step
  const uint64_t step =
      static_cast<uint64_t>(std::llround(d->time / m->opt.timestep));
  const int oldest = (ring_next_ + 1) % (latency_steps_ + 1);
  const double dt = m->opt.timestep;
  for (size_t ri = 0; ri < robots.size(); ++ri) {
    const ServoRobot& r = *robots[ri];
    target_ring_[ri][ring_next_] = r.targets;
    const std::vector<double>& targets = target_ring_[ri][oldest];
    for (size_t j = 0; j < r.servos.size(); ++j) {
      const HingeServo& s = r.servos[j];
      double e = targets[j] - d->qpos[s.qpos];
      // Backlash: the output turns freely within +-backlash/2 of the motor.
      const double half = gap_.backlash / 2;
      e = std::abs(e) <= half ? 0.0 : e - std::copysign(half, e);
      double u = s.kp * e;
      if (gap_.motor_noise > 0) {
        u += gap_.motor_noise *
             GapNormal(gap_.seed, step, (r.id << 32) | (1ull << 31) | j);
      }
      u = std::clamp(u, -s.max_vel, s.max_vel);
      if (gap_.max_accel > 0) {
        const double prev = d->ctrl[s.actuator];
        u = std::clamp(u, prev - gap_.max_accel * dt,
                       prev + gap_.max_accel * dt);
      }
      d->ctrl[s.actuator] = u;
    }
  }
  ring_next_ = (ring_next_ + 1) % (latency_steps_ + 1);
}

void RealityGapEffect::AdjustReadings(
    uint64_t step, uint64_t robot,
    const std::vector<std::vector<double>>& max_distance,
    RobotState* state) const {
  AddSensorNoise(gap_, step, static_cast<int>(robot), max_distance, state);
}

void RealityGapEffect::Restart(const std::vector<const ServoRobot*>& robots) {
  ring_next_ = 0;
  target_ring_.assign(robots.size(), {});
  for (size_t r = 0; r < robots.size(); ++r) {
    target_ring_[r].assign(latency_steps_ + 1, robots[r]->targets);
  }
}

void RealityGapEffect::Absorb(const PhysicsEffect& from,
                              const std::vector<int>& to_robot) {
  const auto& other = static_cast<const RealityGapEffect&>(from);
  for (size_t r = 0; r < to_robot.size(); ++r) {
    const int k = to_robot[r];
    if (k >= 0 && static_cast<size_t>(k) < target_ring_.size() &&
        r < other.target_ring_.size()) {
      target_ring_[k] = other.target_ring_[r];
    }
  }
  ring_next_ = other.ring_next_;
}

Scenario PerturbScenario(const Scenario& scenario, const RealityGap& gap) {
  gap.Validate();
  Scenario s = scenario;
  Factors draw(gap.seed);
  // A fixed order (the scenario's), so the same gap gives the same world.
  for (ContactFriction& c : s.contact_frictions) {
    const double f = draw(gap.friction_range);
    c.friction *= f;
    c.forward_friction *= f;
    c.backward_friction *= f;
    c.lateral_friction *= f;
  }
  for (Robot& r : s.robots) {
    for (Module& m : r.modules) {
      for (Frame& f : m.frames) f.mass *= draw(gap.mass_range);
      if (m.joint.type == JointType::kHinge) {
        m.joint.kp *= draw(gap.gain_range);
        m.joint.velocity_gain *= draw(gap.gain_range);
        m.joint.max_torque *= draw(gap.gain_range);
      }
    }
    for (SensorModule& sm : r.sensor_modules) {
      sm.mass *= draw(gap.mass_range);
      if (sm.force_sensor) sm.force_sensor->mass *= draw(gap.mass_range);
    }
  }
  for (SceneObject& o : s.scene_objects) o.mass *= draw(gap.mass_range);
  s.scene.height *= draw(gap.terrain_range);
  return s;
}

}  // namespace mrsim
