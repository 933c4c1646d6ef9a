// The gaits on real MuJoCo physics: an 11-module MakeChain snake on flat
// ground (pitch chain for forward/backward, pitch-yaw chain for the motions
// that need yaw joints), a few seconds of sim time each.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"

namespace mrsim {
namespace {

constexpr double kPeriod = 0.01;  // control period, s
constexpr double kDeg = 180.0 / M_PI;

std::unique_ptr<Physics> MakeSnake(ChainPattern pattern) {
  ChainOptions options;
  options.modules = 11;
  options.pattern = pattern;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(options));
  return std::make_unique<Physics>(scenario);
}

// Runs a motion from rest: `settle` seconds to let the ramps finish and the
// body take its shape, then `seconds` measured (whole gait periods, so the
// wave's own wobble cancels).
GaitRunResult RunMotion(ChainPattern pattern, const std::string& preset,
                        std::optional<Motion> motion, double strength,
                        double seconds, double settle = 0.0) {
  auto physics = MakeSnake(pattern);
  GaitController controller(JointAxes(*physics, 0));
  controller.SetGait(*FindGaitPreset(preset));
  if (motion) controller.SetMotion(*motion, strength);
  if (settle > 0) RunGait(*physics, 0, controller, settle, kPeriod);
  return RunGait(*physics, 0, controller, seconds, kPeriod);
}

TEST(GaitPhysics, ForwardAndBackwardMoveOppositeWaysAlongTheBody) {
  // The body axis of a MakeChain robot is +x (module 0, the head, in front).
  const auto fwd =
      RunMotion(ChainPattern::kPitch, "forward", Motion::kForward, 1, 8);
  const auto back =
      RunMotion(ChainPattern::kPitch, "forward", Motion::kBackward, 1, 8);
  const Eigen::Vector3d f = fwd.com_end - fwd.com_start;
  const Eigen::Vector3d b = back.com_end - back.com_start;
  std::printf(
      "8 s from rest: forward dx %.3f dy %.3f, backward dx %.3f dy "
      "%.3f m\n",
      f.x(), f.y(), b.x(), b.y());
  EXPECT_GT(f.x(), 0.08) << f.transpose();
  EXPECT_LT(b.x(), -0.08) << b.transpose();
  EXPECT_LT(std::abs(f.y()), 0.2 * f.x());
  EXPECT_LT(std::abs(b.y()), 0.2 * -b.x());
  EXPECT_LT(std::abs(fwd.heading_change) * kDeg, 3.0);
}

TEST(GaitPhysics, TurnsChangeHeadingWithOppositeSignsSharpMoreThanWide) {
  // Turning needs yaw joints: a pitch-yaw chain. Wide = strength 0.375
  // (0.3 rad, turn-wide's offset), sharp = 1 (0.8 rad, turn-sharp's).
  // Curling up while the offsets ramp in swings the heading the other way
  // first, so the turn is measured from t = 4 s (one period) for 6 s.
  auto turn = [](Motion m, double strength) {
    return RunMotion(ChainPattern::kPitchYaw, "forward", m, strength, 6, 4)
        .heading_change;
  };
  const double left_wide = turn(Motion::kTurnLeft, 0.375);
  const double left_sharp = turn(Motion::kTurnLeft, 1);
  const double right_wide = turn(Motion::kTurnRight, 0.375);
  const double right_sharp = turn(Motion::kTurnRight, 1);
  std::printf(
      "heading change over 6 s: left %.1f/%.1f, right %.1f/%.1f deg "
      "(wide/sharp)\n",
      left_wide * kDeg, left_sharp * kDeg, right_wide * kDeg,
      right_sharp * kDeg);
  // Left = heading increases (counter-clockwise seen from above).
  EXPECT_GT(left_wide * kDeg, 3.0);
  EXPECT_GT(left_sharp * kDeg, 1.3 * left_wide * kDeg);
  EXPECT_LT(right_wide * kDeg, -3.0);
  EXPECT_LT(right_sharp * kDeg, 1.3 * right_wide * kDeg);
}

TEST(GaitPhysics, SidewindingMovesMostlySideways) {
  for (Motion m : {Motion::kSidewindLeft, Motion::kSidewindRight}) {
    const auto r = RunMotion(ChainPattern::kPitchYaw, "sidewind", m, 1, 8);
    const Eigen::Vector3d d = r.com_end - r.com_start;
    // The body starts along x: sideways is y, left is +y.
    const double side = m == Motion::kSidewindLeft ? d.y() : -d.y();
    std::printf("8 s from rest: %s dx %.3f dy %.3f m\n", ToString(m), d.x(),
                d.y());
    EXPECT_GT(side, 0.2) << ToString(m) << " " << d.transpose();
    EXPECT_GT(side, 3 * std::abs(d.x())) << ToString(m) << " " << d.transpose();
  }
}

TEST(GaitPhysics, RollingTurnsTheBodyAboutItsLongAxis) {
  const auto r =
      RunMotion(ChainPattern::kPitchYaw, "rolling", std::nullopt, 1, 8);
  std::printf("8 s from rest: rolling turns %.0f deg about the body axis\n",
              r.roll_change * kDeg);
  // At least one whole turn about the body axis.
  EXPECT_GT(std::abs(r.roll_change) * kDeg, 360.0) << r.roll_change * kDeg;
  // For comparison, going forward does not roll.
  const auto f =
      RunMotion(ChainPattern::kPitchYaw, "forward", Motion::kForward, 1, 8);
  EXPECT_LT(std::abs(f.roll_change) * kDeg, 90.0) << f.roll_change * kDeg;
}

TEST(GaitPhysics, SwitchingGaitsMidRunKeepsEveryTargetContinuous) {
  auto physics = MakeSnake(ChainPattern::kPitchYaw);
  GaitController controller(JointAxes(*physics, 0));
  const double limit = controller.options().max_target_rate * kPeriod + 1e-12;
  std::vector<double> prev(controller.joint_count(), 0.0);
  double largest = 0;
  double moved = 0;
  auto observe = [&](const Physics&, const std::vector<double>& t) {
    for (size_t j = 0; j < t.size(); ++j) {
      largest = std::max(largest, std::abs(t[j] - prev[j]));
      moved = std::max(moved, std::abs(t[j]));
    }
    prev = t;
  };
  controller.SetGait(*FindGaitPreset("forward-strong"));
  RunGait(*physics, 0, controller, 1.5, kPeriod, observe);
  controller.SetMotion(Motion::kTurnLeft, 1);
  RunGait(*physics, 0, controller, 0.5, kPeriod, observe);
  controller.SetGait(*FindGaitPreset("sidewind-2"));
  RunGait(*physics, 0, controller, 0.5, kPeriod, observe);
  controller.SetMotion(Motion::kSidewindRight);
  RunGait(*physics, 0, controller, 0.5, kPeriod, observe);
  controller.SetGait(*FindGaitPreset("rolling"));
  RunGait(*physics, 0, controller, 0.5, kPeriod, observe);
  controller.SetMotion(Motion::kBackward, 0.5);
  RunGait(*physics, 0, controller, 0.5, kPeriod, observe);
  controller.SetMotion(Motion::kStop);
  RunGait(*physics, 0, controller, 3.0, kPeriod, observe);
  EXPECT_LE(largest, limit);
  EXPECT_GT(moved, 1.0);  // the gaits did run
  for (double t : prev) EXPECT_EQ(t, 0.0);
  for (int j = 0; j < physics->joint_count(0); ++j) {
    EXPECT_EQ(physics->joint_targets(0)[j], 0.0);
  }
}

}  // namespace
}  // namespace mrsim
