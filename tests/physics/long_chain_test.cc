// Chains of any length: a 200-module pitch-yaw chain with a sensor module
// after every module validates, exports MJCF that MuJoCo's own compiler
// accepts, runs in mrsim-sim and crawls forward with the forward gait.
// (LCM port 7920 for the process test.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/physics/physics.h"
#include "tests/common/child_process.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;

Scenario LongChain(int modules) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = modules;
  options.pattern = ChainPattern::kPitchYaw;
  for (int i = 0; i < modules; ++i) options.sensor_after.push_back(i);
  s.robots.push_back(MakeChain(options));
  return s;
}

TEST(PhysicsLongChain, TwoHundredModulesCompileAndCrawlForward) {
  auto physics = std::make_unique<Physics>(LongChain(200));
  EXPECT_EQ(physics->joint_count(0), 200);
  GaitController controller(JointAxes(*physics, 0));
  controller.SetGait(*FindGaitPreset("forward"));
  controller.SetMotion(Motion::kForward, 1);
  RunGait(*physics, 0, controller, 2.0);  // ramps in, takes its shape
  const GaitRunResult run = RunGait(*physics, 0, controller, 4.0);
  const Eigen::Vector3d d = run.com_end - run.com_start;
  std::printf("200 modules, 4 s forward: dx %.3f dy %.3f m\n", d.x(), d.y());
  EXPECT_GT(d.x(), 0.05);
  EXPECT_LT(std::abs(d.y()), std::abs(d.x()));
}

TEST(PhysicsLongChain, SubTreeWeldsHoldAsRigidlyAsTreeLocks) {
  // 25 yaw modules with sensor modules nest 75 bodies deep: the model is
  // cut once into welded sub-trees. Hanging sideways from a static first
  // frame, gravity loads every lock (the yaw servos do not bend that way).
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 25;
  options.pattern = ChainPattern::kYaw;
  for (int i = 0; i < 25; ++i) options.sensor_after.push_back(i);
  options.origin = Eigen::Vector3d(0, 0, 0.5);
  s.robots.push_back(MakeChain(options));
  s.robots[0].modules[0].frames[0].is_static = true;
  Physics physics(s);
  const mjModel* m = physics.model();
  int weld = -1;
  for (int e = 0; e < m->neq; ++e) {
    const std::string name = mj_id2name(m, mjOBJ_EQUALITY, e);
    if (name.rfind("snake/weld/", 0) == 0) weld = e;
  }
  ASSERT_GE(weld, 0) << "no cut: the chain fits in one tree";
  const int b1 = m->eq_obj1id[weld], b2 = m->eq_obj2id[weld];
  auto relative = [&](int a, int b) {
    const mjData* d = physics.data();
    Eigen::Map<const Eigen::Vector3d> pa(d->xpos + 3 * a), pb(d->xpos + 3 * b);
    const Eigen::Quaterniond qa(d->xquat[4 * a], d->xquat[4 * a + 1],
                                d->xquat[4 * a + 2], d->xquat[4 * a + 3]);
    const Eigen::Quaterniond qb(d->xquat[4 * b], d->xquat[4 * b + 1],
                                d->xquat[4 * b + 2], d->xquat[4 * b + 3]);
    return std::make_pair(Eigen::Vector3d(qa.conjugate() * (pb - pa)),
                          qa.conjugate() * qb);
  };
  const auto before = relative(b1, b2);
  physics.Step(500);
  const auto after = relative(b1, b2);
  const double shift = (after.first - before.first).norm();
  const double turn = after.second.angularDistance(before.second);
  std::printf("welded lock under load: %.2e m, %.2e rad\n", shift, turn);
  EXPECT_LT(shift, 2e-4);
  EXPECT_LT(turn, 5e-3);
  // The chain hangs: the hinges held it straight, nothing fell apart.
  const RobotState st = physics.ReadRobotState(0);
  EXPECT_GT(st.frames.back().position.z(), 0.3);
}

TEST(PhysicsLongChain, ToolsAndSimulatorAcceptTwoHundredModules) {
  const std::string dir = testing::TempDir("long_chain");
  const std::string scenario = dir + "/chain200.xml";
  const std::string tool = BinaryPath("sim_core/scenario_tool/mrsim-scenario");
  {
    ChildProcess make({tool, "new", "--modules", "200", "--pattern",
                       "pitch-yaw", "--sensors", "all", "-o", scenario},
                      dir + "/new.log");
    ASSERT_EQ(make.Wait(60), 0) << make.Output();
  }
  {
    ChildProcess validate({tool, "validate", scenario}, dir + "/validate.log");
    ASSERT_EQ(validate.Wait(60), 0) << validate.Output();
    EXPECT_NE(validate.Output().find(": ok"), std::string::npos);
  }
  {
    ChildProcess exp({tool, "export-mjcf", scenario, "-o", dir + "/c.xml"},
                     dir + "/export.log");
    ASSERT_EQ(exp.Wait(60), 0) << exp.Output();
  }
  {
    ChildProcess compile(
        {"/usr/bin/mujoco-compile", dir + "/c.xml", dir + "/c.mjb"},
        dir + "/compile.log");
    ASSERT_EQ(compile.Wait(120), 0) << compile.Output();
    EXPECT_EQ(compile.Output().find("rror"), std::string::npos)
        << compile.Output();
  }
  // A few periods show it runs the chain; the crawl test above covers
  // seconds of it in process.
  ChildProcess sim(
      {BinaryPath("sim_core/sim_process/mrsim-sim"), scenario, "--lcm-url",
       testing::TestLcmUrl(7920), "--clock", "fast", "--duration", "0.1"},
      dir + "/sim.log");
  EXPECT_EQ(sim.Wait(120), 0) << sim.Output();
  EXPECT_NE(sim.Output().find("stopped (duration reached)"), std::string::npos)
      << sim.Output();
}

}  // namespace
}  // namespace mrsim
