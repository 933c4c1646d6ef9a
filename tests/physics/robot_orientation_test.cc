// The state's whole-robot orientation (docs/sim.md, "The robot's
// orientation"): a robot placed turned reports that turn from t=0 on, and
// keeps reporting where it faces while it drives.
#include "sim_core/physics/robot_orientation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"

namespace mrsim {
namespace {

constexpr double kControlPeriod = 0.01;

// A pitch chain, turned by `turn` rad about the vertical through module 0's
// hinge, as the studio's heading ring turns a robot.
Scenario TurnedChain(double turn, int modules) {
  ChainScenarioOptions options;
  options.chain.modules = modules;
  options.friction = 0.8;
  Scenario s = MakeChainScenario(options);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()));
  for (Module& m : s.robots.at(0).modules) {
    m.position = q * m.position;
    for (Frame& f : m.frames) {
      f.position = q * f.position;
      f.quat_rotation = q * f.quat_rotation;
    }
  }
  return s;
}

void ExpectQuaternionNear(const Eigen::Quaterniond& got,
                          const Eigen::Quaterniond& want, double tolerance) {
  // q and -q are the same turn; the state reports w >= 0.
  EXPECT_GE(got.w(), 0.0);
  EXPECT_NEAR(got.w(), want.w(), tolerance);
  EXPECT_NEAR(got.x(), want.x(), tolerance);
  EXPECT_NEAR(got.y(), want.y(), tolerance);
  EXPECT_NEAR(got.z(), want.z(), tolerance);
}

TEST(RobotOrientation, RobotTurnedAboutZReportsTheTurnAtStartAndAtRest) {
  Physics physics(TurnedChain(M_PI / 2, 5));
  const Eigen::Quaterniond want(std::cos(M_PI / 4), 0, 0, std::sin(M_PI / 4));
  const RobotState start = physics.ReadRobotState(0);
  ExpectQuaternionNear(start.orientation, want, 1e-9);
  EXPECT_NEAR(start.heading, M_PI / 2, 1e-9);

  physics.Step(500);  // 1 s holding every joint at 0: it settles, no turn
  const RobotState later = physics.ReadRobotState(0);
  ExpectQuaternionNear(later.orientation, want, 1e-3);
  EXPECT_NEAR(later.heading, M_PI / 2, 1e-3);
}

TEST(RobotOrientation, UnturnedChainFacesPlusXWithIdentity) {
  Physics physics(TurnedChain(0.0, 3));
  const RobotState s = physics.ReadRobotState(0);
  ExpectQuaternionNear(s.orientation, Eigen::Quaterniond::Identity(), 1e-9);
  EXPECT_NEAR(s.heading, 0.0, 1e-9);
}

// Driving forward with the "forward" gait, the turned robot's heading stays
// where it faces (its body's tail-to-head direction) and it travels along
// that heading, +y.
TEST(RobotOrientation, TurnedRobotDrivingForwardKeepsItsHeading) {
  Physics physics(TurnedChain(M_PI / 2, 11));
  GaitController controller(JointAxes(physics, 0));
  controller.SetGait(*FindGaitPreset("forward"));
  double worst = 0.0;
  const GaitRunResult r = RunGait(
      physics, 0, controller, 4.0, kControlPeriod,
      [&worst](const Physics& p, const std::vector<double>&) {
        const RobotState s = p.ReadRobotState(0);
        EXPECT_NEAR(s.heading, HeadingOf(s.orientation), 1e-12);
        worst = std::max(
            worst, std::abs(std::remainder(s.heading - M_PI / 2, 2 * M_PI)));
      });
  const Eigen::Vector3d travel = r.com_end - r.com_start;
  EXPECT_GT(travel.y(), 0.05) << "it drove forward";
  EXPECT_LT(std::abs(travel.x()), 0.2 * travel.y()) << "along its heading";
  // The head nods up and down with the pitch wave but does not turn.
  EXPECT_LT(worst, 0.1) << "rad away from +y at worst";
  const RobotState end = physics.ReadRobotState(0);
  EXPECT_NEAR(std::remainder(end.heading - BodyHeading(end), 2 * M_PI), 0.0,
              0.1);
}

TEST(RobotOrientation, HeadingIsTheYawOfTheForwardAxis) {
  const Eigen::Quaterniond yaw(
      Eigen::AngleAxisd(-2.0, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond nod(
      Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(HeadingOf(yaw * nod), -2.0, 1e-12);  // nodding keeps the yaw
  const Eigen::Quaterniond up(
      Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()));
  EXPECT_EQ(HeadingOf(up), 0.0);  // pointing straight up: no heading
}

}  // namespace
}  // namespace mrsim
