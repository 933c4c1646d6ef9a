#include "gait_controller/gait_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "gait_controller/gait_presets.h"

namespace mrsim {
namespace {

constexpr double kDt = 0.01;

std::vector<Axis> PitchChain(int n) {
  return std::vector<Axis>(n, Axis::kPitch);
}

std::vector<Axis> PitchYawChain(int n) {
  std::vector<Axis> axes;
  for (int i = 0; i < n; ++i) axes.push_back(i % 2 ? Axis::kYaw : Axis::kPitch);
  return axes;
}

// Runs the controller for `seconds` and returns the largest change of any
// target between two updates.
double RunAndMeasureMaxStep(GaitController& c, double seconds) {
  double max_step = 0;
  std::vector<double> prev = c.targets();
  const int n = static_cast<int>(std::lround(seconds / kDt));
  for (int k = 0; k < n; ++k) {
    const auto& t = c.Update(kDt);
    for (size_t j = 0; j < t.size(); ++j) {
      max_step = std::max(max_step, std::abs(t[j] - prev[j]));
    }
    prev = t;
  }
  return max_step;
}

void ExpectFollowsGoal(const GaitController& c) {
  const auto& goal = c.goal_waves();
  for (int j = 0; j < c.joint_count(); ++j) {
    const double want =
        goal[j].amplitude * std::sin(c.phase() + goal[j].shift) +
        goal[j].offset;
    EXPECT_NEAR(c.targets()[j], want, 1e-12) << "joint " << j;
  }
}

TEST(GaitController, SettlesOnTheSinusoidOfTheFormula) {
  GaitController c(PitchChain(11));
  EXPECT_EQ(c.targets(), std::vector<double>(11, 0.0));
  RunAndMeasureMaxStep(c, 3.0);
  ASSERT_TRUE(c.settled());
  const double period = c.active_gait().parameters.period;
  for (int k = 0; k < 50; ++k) {
    const double before = c.phase();
    c.Update(kDt);
    // The phase advances 2 pi dt / T per update (mod 2 pi).
    EXPECT_NEAR(
        std::remainder(c.phase() - before - 2 * M_PI * kDt / period, 2 * M_PI),
        0.0, 1e-12);
    for (int j = 0; j < 11; ++j) {
      const double want = 1.0 * std::sin(c.phase() + j * 2.5);
      EXPECT_NEAR(c.targets()[j], want, 1e-12);
    }
  }
}

TEST(GaitController, SameCommandsGiveIdenticalTargets) {
  auto run = [] {
    GaitController c(PitchYawChain(11));
    std::vector<double> all;
    for (int k = 0; k < 600; ++k) {
      if (k == 100) c.SetMotion(Motion::kTurnLeft, 0.6);
      if (k == 250) c.SetGait(*FindGaitPreset("sidewind-2"));
      if (k == 400) c.SetMotion(Motion::kStop);
      const auto& t = c.Update(kDt);
      all.insert(all.end(), t.begin(), t.end());
    }
    return all;
  };
  EXPECT_EQ(run(), run());
}

TEST(GaitController, SwitchingNeverStepsBeyondTheRateLimit) {
  GaitController c(PitchYawChain(11));
  const double limit = c.options().max_target_rate * kDt + 1e-12;
  c.SetGait(*FindGaitPreset("forward-strong"));
  EXPECT_LE(RunAndMeasureMaxStep(c, 2.5), limit);
  // Every kind of switch, each before the previous one has settled.
  const std::vector<std::function<void()>> switches = {
      [&] { c.SetMotion(Motion::kBackward); },
      [&] { c.SetMotion(Motion::kTurnLeft, 1.0); },
      [&] { c.SetMotion(Motion::kTurnRight, 0.5); },
      [&] { c.SetGait(*FindGaitPreset("sidewind-2")); },
      [&] { c.SetMotion(Motion::kSidewindRight); },
      [&] { c.SetMotion(Motion::kRoll, -1.0); },
      [&] {
        c.SetParameters(
            GaitParameters::FromVector({2.5, 2.0, -3, 6, 0.5, 0.7, -0.9}));
      },
      [&] { c.SetDirection(-0.3, 0.8); },
      [&] { c.SetMotion(Motion::kForward); },
      [&] { c.SetMotion(Motion::kStop); },
      [&] { c.SetGait(*FindGaitPreset("turn-sharp")); },
  };
  for (size_t i = 0; i < switches.size(); ++i) {
    switches[i]();
    EXPECT_LE(RunAndMeasureMaxStep(c, 0.37), limit) << "switch " << i;
  }
  // And the last switch completes: the targets follow the new gait.
  RunAndMeasureMaxStep(c, 5.0);
  ASSERT_TRUE(c.settled());
  EXPECT_EQ(c.active_gait().name, "turn-sharp");
  ExpectFollowsGoal(c);
}

TEST(GaitController, StopBringsEveryJointSmoothlyToZero) {
  GaitController c(PitchYawChain(11));
  c.SetGait(*FindGaitPreset("sidewind-2"));
  RunAndMeasureMaxStep(c, 3.0);
  c.SetMotion(Motion::kStop);
  EXPECT_TRUE(c.stopped());
  EXPECT_LE(RunAndMeasureMaxStep(c, 3.0),
            c.options().max_target_rate * kDt + 1e-12);
  for (double t : c.targets()) EXPECT_EQ(t, 0.0);
  c.Update(kDt);
  for (double t : c.targets()) EXPECT_EQ(t, 0.0);
}

TEST(GaitController, BackwardRunsThePhaseTheOtherWay) {
  GaitController c(PitchChain(5));
  RunAndMeasureMaxStep(c, 2.0);
  const double fwd_before = c.phase();
  c.Update(kDt);
  const double fwd_step = std::remainder(c.phase() - fwd_before, 2 * M_PI);
  EXPECT_GT(fwd_step, 0);
  c.SetMotion(Motion::kBackward);
  RunAndMeasureMaxStep(c, 2.0);
  EXPECT_EQ(c.motion(), Motion::kBackward);
  const double back_before = c.phase();
  c.Update(kDt);
  EXPECT_NEAR(std::remainder(c.phase() - back_before, 2 * M_PI), -fwd_step,
              1e-12);
  // Same shape, so the switch did not move the wave's spatial pattern.
  ExpectFollowsGoal(c);
}

TEST(GaitController, TurnOffsetsOnlyTheYawJoints) {
  GaitController c(PitchYawChain(6));
  c.SetMotion(Motion::kTurnLeft, 0.5);
  const auto& g = c.goal_waves();
  // Left is a negative yaw offset (docs/gait.md).
  const double o = -0.5 * c.options().max_turn_offset;
  for (int j = 0; j < 6; ++j) {
    EXPECT_DOUBLE_EQ(g[j].offset, j % 2 ? o : 0.0) << j;
    EXPECT_DOUBLE_EQ(g[j].amplitude, j % 2 ? 0.0 : 1.0) << j;
  }
  c.SetMotion(Motion::kTurnRight, 0.5);
  EXPECT_DOUBLE_EQ(c.goal_waves()[1].offset, -o);
  c.SetDirection(0.2, -1.0);
  EXPECT_EQ(c.motion(), Motion::kTurnRight);
  EXPECT_DOUBLE_EQ(c.goal_waves()[3].offset, c.options().max_turn_offset);
}

TEST(GaitController, PeriodChangeKeepsThePhaseContinuous) {
  GaitController c(PitchChain(4));
  RunAndMeasureMaxStep(c, 2.0);
  GaitParameters p = c.active_gait().parameters;
  p.period = 1.0;
  c.SetParameters(p);
  EXPECT_EQ(c.active_gait().name, "custom");
  const double before = c.phase();
  c.Update(kDt);
  EXPECT_NEAR(std::remainder(c.phase() - before, 2 * M_PI),
              2 * M_PI * kDt / 1.0, 1e-12);
}

TEST(GaitController, GaitKindSelectsTheMotion) {
  GaitController c(PitchYawChain(11));
  c.SetGait(*FindGaitPreset("rolling"));
  EXPECT_EQ(c.motion(), Motion::kRoll);
  EXPECT_EQ(c.active_kind(), GaitKind::kRoll);
  c.SetGait(*FindGaitPreset("sidewind-1"));
  EXPECT_EQ(c.motion(), Motion::kSidewindLeft);
  EXPECT_EQ(c.active_gait().name, "sidewind-1");
  c.SetMotion(Motion::kForward);
  EXPECT_EQ(c.active_gait().name, "forward");
  c.SetMotion(Motion::kSidewindRight);
  EXPECT_EQ(c.active_gait().name, "sidewind-1");
  // Loading a linear gait while sidewinding goes back to forward.
  c.SetGait(*FindGaitPreset("turn-wide"));
  EXPECT_EQ(c.motion(), Motion::kForward);
  EXPECT_EQ(c.active_gait().name, "turn-wide");
}

TEST(GaitController, BadCommandsThrowAndChangeNothing) {
  GaitController c(PitchChain(11));
  c.SetMotion(Motion::kBackward, 0.5);
  EXPECT_THROW(c.SetMotion(Motion::kForward, 1.5), std::invalid_argument);
  EXPECT_THROW(c.SetMotion(Motion::kForward, std::nan("")),
               std::invalid_argument);
  EXPECT_THROW(c.SetDirection(0, -2), std::invalid_argument);
  EXPECT_EQ(c.motion(), Motion::kBackward);
  EXPECT_EQ(c.strength(), 0.5);
  GaitParameters bad = c.active_gait().parameters;
  bad.period = std::nan("");
  EXPECT_THROW(c.SetParameters(bad), std::invalid_argument);
  Gait g = *FindGaitPreset("forward-strong");
  g.parameters.overrides.push_back({11, 0.1, std::nullopt, std::nullopt});
  EXPECT_THROW(c.SetGait(g), std::invalid_argument);
  EXPECT_EQ(c.active_gait().name, "forward");
  EXPECT_THROW(c.Update(-0.01), std::invalid_argument);
  EXPECT_THROW(c.Update(INFINITY), std::invalid_argument);
  EXPECT_THROW(GaitController(std::vector<Axis>{}), std::invalid_argument);
}

TEST(GaitController, TargetsStayWithinTheLimit) {
  GaitController c(PitchChain(3));
  c.SetParameters(GaitParameters::FromVector({3, 0, 1, 0, 1, 3, 0}));
  double largest = 0;
  for (int k = 0; k < 800; ++k) {
    for (double t : c.Update(kDt)) largest = std::max(largest, std::abs(t));
  }
  EXPECT_LE(largest, c.options().target_limit);
  EXPECT_GT(largest, 3.0);
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

TEST(GaitControllerState, SavedAndLoadedContinuesBitForBit) {
  const std::vector<Axis> axes = {Axis::kPitch, Axis::kYaw, Axis::kPitch,
                                  Axis::kYaw, Axis::kPitch};
  GaitController a(axes);
  a.SetGait(*FindGaitPreset("sidewind-2"));
  for (int k = 0; k < 137; ++k) a.Update(0.01);
  a.SetMotion(Motion::kTurnLeft, 0.6);  // mid-transition when saved
  for (int k = 0; k < 23; ++k) a.Update(0.01);
  GaitController b(axes);
  b.LoadState(a.SaveState());
  EXPECT_EQ(b.SaveState(), a.SaveState());
  for (int k = 0; k < 300; ++k) {
    ASSERT_EQ(a.Update(0.01), b.Update(0.01)) << k;
  }
  EXPECT_EQ(b.motion(), Motion::kTurnLeft);
  GaitController other(std::vector<Axis>(3, Axis::kPitch));
  EXPECT_THROW(other.LoadState(a.SaveState()), std::invalid_argument);
  EXPECT_THROW(other.LoadState("garbage"), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim
