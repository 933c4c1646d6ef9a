// The CPG gait: coupled phase oscillators converge to the designed lags
// from any start, stay smooth when the drive jumps, and the sensory
// feedback term slows or stops the rhythm as docs/gait.md says.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gait_controller/cpg_feedback.h"
#include "gait_controller/cpg_network.h"
#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"

namespace mrsim {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

std::vector<Axis> PitchYaw(int n) {
  std::vector<Axis> axes;
  for (int i = 0; i < n; ++i) axes.push_back(i % 2 ? Axis::kYaw : Axis::kPitch);
  return axes;
}

// Largest error between the phase differences of neighbours and the lags
// the goal waves design.
double LagError(const CpgNetwork& net, const std::vector<JointWave>& goal) {
  double worst = 0;
  for (int i = 1; i < net.joints(); ++i) {
    const double got = net.phases()[i] - net.phases()[i - 1];
    const double want = goal[i].shift - goal[i - 1].shift;
    worst = std::max(worst, std::abs(std::remainder(got - want, kTwoPi)));
  }
  return worst;
}

TEST(CpgNetwork, RandomInitialPhasesConvergeToTheDesignedLags) {
  Gait sidewind = *FindGaitPreset("sidewind");
  const std::vector<JointWave> goal =
      JointWaves(sidewind.parameters, PitchYaw(12));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0, kTwoPi);
  for (int trial = 0; trial < 5; ++trial) {
    CpgNetwork net(12);
    std::vector<double> start(12);
    for (double& p : start) p = phase(rng);
    net.SetPhases(start);
    ASSERT_GT(LagError(net, goal), 0.3);
    for (int k = 0; k < 3000; ++k) net.Step(0.01, goal, 0.25, CpgParameters{});
    EXPECT_LT(LagError(net, goal), 1e-3) << "trial " << trial;
    // And the rhythm runs at the goal frequency.
    EXPECT_NEAR(net.frequency(), 0.25, 1e-6);
  }
}

TEST(CpgNetwork, StrongerCouplingConvergesFaster) {
  const std::vector<JointWave> goal =
      JointWaves(FindGaitPreset("forward")->parameters, PitchYaw(8));
  auto error_after = [&](double coupling) {
    CpgNetwork net(8);
    net.SetPhases({0, 3, 1, 5, 2, 4, 0.5, 6});
    CpgParameters p;
    p.coupling = coupling;
    for (int k = 0; k < 300; ++k) net.Step(0.01, goal, 0.25, p);
    return LagError(net, goal);
  };
  EXPECT_LT(error_after(8.0), error_after(2.0));
}

TEST(CpgGait, DriveJumpKeepsTargetsAndSpeedsContinuous) {
  Gait gait = *FindGaitPreset("cpg-forward");
  GaitControllerOptions options;
  options.max_target_rate = 100;  // so only the CPG shapes the targets
  GaitController c(PitchYaw(10), options);
  c.SetGait(gait);
  c.SetMotion(Motion::kForward, 0.3);
  const double dt = 0.01;
  for (int k = 0; k < 2000; ++k) c.Update(dt);
  ASSERT_TRUE(c.cpg_running());
  // Largest change per step of target and of target speed, before and
  // across a jump of the drive from 0.3 to 1.
  auto run = [&](int steps, double* max_step, double* max_accel) {
    std::vector<double> last = c.targets();
    std::vector<double> last_speed(last.size(), 0.0);
    for (int j = 0; j < c.joint_count(); ++j) {
      last_speed[j] = c.cpg().output_rate(j);
    }
    *max_step = 0;
    *max_accel = 0;
    for (int k = 0; k < steps; ++k) {
      c.Update(dt);
      for (int j = 0; j < c.joint_count(); ++j) {
        const double speed = c.cpg().output_rate(j);
        *max_step = std::max(*max_step, std::abs(c.targets()[j] - last[j]));
        *max_accel = std::max(*max_accel, std::abs(speed - last_speed[j]));
        last[j] = c.targets()[j];
        last_speed[j] = speed;
      }
    }
  };
  double step_before = 0, accel_before = 0, step_jump = 0, accel_jump = 0;
  run(400, &step_before, &accel_before);
  c.SetMotion(Motion::kForward, 1.0);
  run(400, &step_jump, &accel_jump);
  // After the jump the waves run 3.3 times faster, so steps grow about
  // that much, but nothing leaps: a step of the speed is of the size the
  // faster rhythm itself makes (a sinusoid's speed changes by A w^2 dt per
  // step), far from the jump of A (w1 - w0) a stepped phase speed gives.
  const double w1 = kTwoPi / gait.parameters.period;
  const double amplitude = gait.parameters.amplitude_pitch;
  EXPECT_LT(step_jump, 1.5 * amplitude * w1 * dt);
  EXPECT_LT(accel_jump, 1.5 * amplitude * w1 * w1 * dt);
  EXPECT_LT(accel_jump, 0.1 * amplitude * w1 * 0.7);
  EXPECT_GT(step_before, 0);
}

TEST(CpgGait, SinusoidToCpgHandOverDoesNotJump) {
  GaitController c(PitchYaw(6));
  for (int k = 0; k < 800; ++k) c.Update(0.01);
  const std::vector<double> before = c.targets();
  c.SetGait(*FindGaitPreset("cpg-forward"));
  c.Update(0.01);
  for (size_t j = 0; j < before.size(); ++j) {
    EXPECT_LT(std::abs(c.targets()[j] - before[j]), 0.05) << "joint " << j;
  }
}

// docs/gait.md: with a constant input s, an oscillator's phase speed is
// omega - sigma s cos(theta); it runs at sqrt(omega^2 - (sigma s)^2) / 2pi
// Hz while sigma s < omega and stops at cos(theta) = omega / (sigma s)
// beyond.
TEST(CpgNetwork, FeedbackSlowsTheRhythmAsDocumentedAndStopsItBeyondOmega) {
  const std::vector<JointWave> goal(1, JointWave{1.0, 0.0, 0.0});
  const double nu = 0.5;
  const double omega = kTwoPi * nu;
  CpgParameters p;
  p.feedback_gain = 2.0;
  auto measured_frequency = [&](double input) {
    CpgNetwork net(1);
    net.Seed({0.0}, goal, nu);
    // Count whole turns of the phase over 40 s after 10 s of settling.
    for (int k = 0; k < 1000; ++k) net.Step(0.01, goal, nu, p, {input});
    double turns = 0;
    double last = net.phases()[0];
    for (int k = 0; k < 4000; ++k) {
      net.Step(0.01, goal, nu, p, {input});
      double d = net.phases()[0] - last;
      if (d < -3) d += kTwoPi;
      turns += d / kTwoPi;
      last = net.phases()[0];
    }
    return turns / 40.0;
  };
  EXPECT_NEAR(measured_frequency(0.0), nu, 0.01);
  const double s = 0.8;  // sigma s = 1.6 < omega = 3.14
  const double expected =
      std::sqrt(omega * omega - std::pow(p.feedback_gain * s, 2)) / kTwoPi;
  EXPECT_NEAR(measured_frequency(s), expected, 0.01);
  EXPECT_LT(measured_frequency(s), nu - 0.05);
  // sigma s = 4 > omega: the phase locks where cos(theta) = omega/(sigma s).
  p.feedback_gain = 4.0;
  CpgNetwork net(1);
  net.Seed({0.0}, goal, nu);
  for (int k = 0; k < 2000; ++k) net.Step(0.01, goal, nu, p, {1.0});
  EXPECT_NEAR(std::cos(net.phases()[0]), omega / 4.0, 1e-3);
  EXPECT_LT(std::sin(net.phases()[0]), 0);
}

TEST(CpgFeedback, ForceAndDistanceGoToTheNearestJoint) {
  RobotState state;
  state.joints.resize(3);
  for (int j = 0; j < 3; ++j) {
    state.joints[j].world.position = Eigen::Vector3d(-0.1 * j, 0, 0);
  }
  SensorModuleState touching;
  touching.pose.position = Eigen::Vector3d(-0.21, 0, 0);
  touching.has_force = true;
  touching.force = 0.5;
  SensorModuleState seeing;
  seeing.pose.position = Eigen::Vector3d(0.02, 0, 0);
  seeing.distances = {0.15, 2.0};
  state.sensor_modules = {touching, seeing};
  CpgParameters p;  // force_scale 1 N, distance_range 0.3 m
  const std::vector<double> in = CpgFeedback(state, p);
  ASSERT_EQ(in.size(), 3u);
  EXPECT_DOUBLE_EQ(in[0], 0.5);  // 1 - 0.15 / 0.3
  EXPECT_DOUBLE_EQ(in[1], 0.0);
  EXPECT_DOUBLE_EQ(in[2], 0.5);  // 0.5 N of 1 N
}

TEST(CpgGait, GaitFileKeepsTheCpgSettingsAndTheTaper) {
  Gait g = *FindGaitPreset("conical-sidewind");
  g.cpg = CpgParameters{};
  g.cpg->coupling = 6.5;
  g.cpg->feedback_gain = -1.25;
  const Gait back = ReadGaitString(WriteGaitString(g), "g.xml");
  EXPECT_EQ(back, g);
}

TEST(CpgGait, GaitFileRejectsABadCpgValueNamingTheLine) {
  const std::string xml =
      "<gait name=\"x\">\n<A_pitch>1</A_pitch><A_yaw>0</A_yaw>"
      "<phi_pitch>1</phi_pitch><phi_yaw>0</phi_yaw><T>4</T>"
      "<offset_pitch>0</offset_pitch><offset_yaw>0</offset_yaw>\n"
      "<cpg coupling=\"-1\"/>\n</gait>";
  try {
    ReadGaitString(xml, "bad.xml");
    FAIL() << "accepted a negative coupling";
  } catch (const GaitFileError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.xml:3"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("coupling"), std::string::npos);
  }
}

TEST(CpgGait, SavedStateContinuesBitForBit) {
  GaitController a(PitchYaw(6));
  a.SetGait(*FindGaitPreset("cpg-serpenoid"));
  a.SetFeedback({0, 0.2, 0, 0, 0.4, 0});
  for (int k = 0; k < 321; ++k) a.Update(0.01);
  GaitController b(PitchYaw(6));
  b.LoadState(a.SaveState());
  for (int k = 0; k < 200; ++k) {
    a.Update(0.01);
    b.Update(0.01);
  }
  EXPECT_EQ(a.targets(), b.targets());
}

TEST(GaitParameters, TaperGrowsTheAmplitudeTowardsTheHead) {
  GaitParameters p = FindGaitPreset("conical-sidewind")->parameters;
  const std::vector<JointWave> w = JointWaves(p, PitchYaw(11));
  EXPECT_NEAR(w[1].amplitude, p.amplitude_yaw * (1 + 0.5 * 0.8), 1e-12);
  EXPECT_NEAR(w[9].amplitude, p.amplitude_yaw * (1 - 0.5 * 0.8), 1e-12);
}

}  // namespace
}  // namespace mrsim
