// The reality gap (docs/physics.md, "The reality gap"): per-episode
// randomisation within its ranges, per-step servo and sensor imperfections,
// and the same seed giving the same run.
#include "sim_core/physics/reality_gap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"

namespace mrsim {
namespace {

Scenario Snake() {
  ChainScenarioOptions o;
  o.chain.modules = 4;
  o.chain.pattern = ChainPattern::kPitchYaw;
  o.friction = 0.6;
  return MakeChainScenario(o);
}

std::vector<double> Targets(int n, int i) {
  std::vector<double> t(n);
  for (int j = 0; j < n; ++j) t[j] = 0.7 * std::sin(0.01 * i - 0.9 * j);
  return t;
}

TEST(RealityGap, PerturbedWorldStaysWithinItsRangesAndFollowsTheSeed) {
  const Scenario s = Snake();
  RealityGap gap = RealityGap::Typical();
  gap.seed = 7;
  const Scenario a = PerturbScenario(s, gap);
  EXPECT_EQ(a, PerturbScenario(s, gap));
  const Scenario b = PerturbScenario(s, gap.ForEpisode(1));
  EXPECT_NE(a, b);
  const double f0 = s.contact_frictions[0].friction;
  const double f = a.contact_frictions[0].friction;
  EXPECT_GE(f, f0 * (1 - gap.friction_range));
  EXPECT_LE(f, f0 * (1 + gap.friction_range));
  for (size_t i = 0; i < s.robots[0].modules.size(); ++i) {
    const Module& m0 = s.robots[0].modules[i];
    const Module& m = a.robots[0].modules[i];
    EXPECT_NEAR(m.frames[0].mass, m0.frames[0].mass,
                m0.frames[0].mass * gap.mass_range + 1e-15);
    EXPECT_NEAR(m.joint.kp, m0.joint.kp, m0.joint.kp * gap.gain_range + 1e-15);
  }
  // No ranges: the very same scenario.
  EXPECT_EQ(PerturbScenario(s, RealityGap{}), s);
}

TEST(RealityGap, SameSeedSameRunOtherSeedOtherRun) {
  auto run = [](uint64_t seed) {
    Physics p(Snake());
    RealityGap gap = RealityGap::Typical();
    gap.seed = seed;
    p.SetRealityGap(gap);
    for (int i = 0; i < 500; ++i) {
      p.SetJointTargets(0, Targets(p.joint_count(0), i));
      p.Step();
    }
    return std::vector<double>(p.data()->qpos, p.data()->qpos + p.model()->nq);
  };
  const std::vector<double> a = run(3);
  EXPECT_EQ(a, run(3));
  EXPECT_NE(a, run(4));
}

TEST(RealityGap, ResetAfterAPerturbedRunIsAFreshRun) {
  // The optimiser's pool resets simulations between episodes.
  RealityGap gap = RealityGap::Typical();
  gap.seed = 5;
  auto drive = [](Physics& p) {
    for (int i = 0; i < 300; ++i) {
      p.SetJointTargets(0, Targets(p.joint_count(0), i));
      p.Step();
    }
  };
  Physics fresh(Snake());
  fresh.SetRealityGap(gap);
  drive(fresh);
  Physics reused(Snake());
  reused.SetRealityGap(gap);
  drive(reused);
  drive(reused);
  reused.Reset();
  drive(reused);
  EXPECT_EQ(std::memcmp(fresh.data()->qpos, reused.data()->qpos,
                        fresh.model()->nq * sizeof(mjtNum)),
            0);
}

// Hinge 0's angle after stepping `seconds` towards a target of `target`.
double AngleAfter(const RealityGap& gap, double target, double seconds) {
  Physics p(Snake());
  p.SetRealityGap(gap);
  std::vector<double> t(p.joint_count(0), 0.0);
  t[0] = target;
  p.SetJointTargets(0, t);
  p.Step(static_cast<int>(std::lround(seconds / p.timestep())));
  return p.data()->qpos[p.model()->jnt_qposadr[mj_name2id(
      p.model(), mjOBJ_JOINT, "snake/m0/hinge")]];
}

TEST(RealityGap, LatencyDelaysTheServo) {
  RealityGap late;
  late.latency = 0.05;
  EXPECT_GT(std::abs(AngleAfter(RealityGap{}, 0.5, 0.04)), 0.05);
  EXPECT_LT(std::abs(AngleAfter(late, 0.5, 0.04)), 0.01);
  EXPECT_NEAR(AngleAfter(late, 0.5, 2.0), AngleAfter(RealityGap{}, 0.5, 2.0),
              0.02);
}

TEST(RealityGap, BacklashIgnoresSmallTargetsAndOffsetsLargeOnes) {
  RealityGap slack;
  slack.backlash = 0.1;
  EXPECT_LT(std::abs(AngleAfter(slack, 0.04, 1.0)), 0.01);
  // A large move stops half the backlash short.
  EXPECT_NEAR(AngleAfter(slack, 0.5, 2.0), 0.45, 0.03);
}

TEST(RealityGap, AccelerationLimitSlowsTheStart) {
  RealityGap slow;
  slow.max_accel = 10;  // rad/s^2: 3 rad/s takes 0.3 s
  const double free = AngleAfter(RealityGap{}, 1.0, 0.1);
  const double limited = AngleAfter(slow, 1.0, 0.1);
  EXPECT_LT(std::abs(limited), 0.5 * 10 * 0.1 * 0.1 + 0.01);
  EXPECT_GT(std::abs(free), 2 * std::abs(limited));
}

TEST(RealityGap, SensorNoiseHasItsSizeAndLeavesThePhysicsAlone) {
  RealityGap noisy;
  noisy.joint_noise = 0.01;
  noisy.seed = 9;
  Physics clean(Snake()), p(Snake());
  p.SetRealityGap(noisy);
  double sum2 = 0;
  int n = 0;
  for (int i = 0; i < 200; ++i) {
    clean.Step();
    p.Step();
    const RobotState a = clean.ReadRobotState(0), b = p.ReadRobotState(0);
    for (size_t j = 0; j < a.joints.size(); ++j) {
      const double e = b.joints[j].angle - a.joints[j].angle;
      sum2 += e * e;
      ++n;
    }
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 0.002);
  // Readings only: the bodies moved exactly alike.
  EXPECT_EQ(clean.CenterOfMass(0), p.CenterOfMass(0));
}

TEST(RealityGap, OutOfRangeSettingsAreRefusedNamingThem) {
  RealityGap g;
  g.friction_range = 1.5;
  try {
    g.Validate();
    FAIL() << "accepted friction_range 1.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("friction_range"), std::string::npos);
  }
  RealityGap nan;
  nan.latency = std::nan("");
  EXPECT_THROW(nan.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim
