// Detachable locks: released and re-made at run time, broken by force,
// carried through checkpoints.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/physics.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

double Gap(const Physics& physics, int frame_a, int frame_b) {
  const RobotState s = physics.ReadRobotState(0);
  return (s.frames[frame_a].position - s.frames[frame_b].position).norm();
}

// A 4-module yaw chain hanging sideways from a static first frame, 0.5 m
// above the ground: gravity loads every lock.
Scenario HangingChain(double middle_break_force = 0) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 4;
  options.pattern = ChainPattern::kYaw;
  options.origin = Eigen::Vector3d(0, 0, 0.5);
  Robot robot = MakeChain(options);
  robot.modules[0].frames[0].is_static = true;
  robot.locks[1].break_force = middle_break_force;  // m1/f1 - m2/f0
  s.robots.push_back(robot);
  return s;
}

TEST(PhysicsLocks, LockStatesListEveryLockInScenarioOrder) {
  Physics physics(HangingChain());
  const auto locks = physics.LockStates("snake");
  ASSERT_EQ(locks.size(), 3u);
  EXPECT_EQ(locks[0].first, "snake/lock0");
  EXPECT_EQ(locks[2].first, "snake/lock2");
  for (const auto& l : locks) EXPECT_TRUE(l.second);
}

TEST(PhysicsLocks, UnknownRobotOrLockIsNamed) {
  Physics physics(HangingChain());
  try {
    physics.SetLockAttached("snake", "nope", false);
    FAIL() << "no error";
  } catch (const PhysicsError& e) {
    EXPECT_NE(std::string(e.what()).find("'nope'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("snake/lock1"), std::string::npos);
  }
  EXPECT_THROW(physics.SetLockAttached("worm", "snake/lock0", false),
               PhysicsError);
  EXPECT_THROW(physics.LockStates("worm"), PhysicsError);
}

TEST(PhysicsLocks, PlaceholderGuidsGetGeneratedNames) {
  Scenario s = HangingChain();
  for (Joint& l : s.robots[0].locks) {
    l.guid = "00000000-0000-0000-0000-000000000000";
  }
  Physics physics(s);
  const auto locks = physics.LockStates("snake");
  ASSERT_EQ(locks.size(), 3u);
  EXPECT_EQ(locks[1].first, "lock1");
  physics.SetLockAttached("snake", "lock1", false);
  EXPECT_FALSE(physics.LockStates("snake")[1].second);
}

TEST(PhysicsLocks, ReleasedChainHalvesMoveApart) {
  Physics physics(HangingChain());
  physics.Step(250);
  // Frames 3 (m1/f1) and 4 (m2/f0) are joined by the middle lock.
  const double held = Gap(physics, 3, 4);
  const double z_before = physics.ReadRobotState(0).frames[7].position.z();
  physics.SetLockAttached("snake", "snake/lock1", false);
  EXPECT_FALSE(physics.LockStates("snake")[1].second);
  EXPECT_TRUE(physics.LockStates("snake")[0].second);
  physics.Step(250);  // 0.5 s: the back half falls 0.45 m to the ground
  const RobotState after = physics.ReadRobotState(0);
  EXPECT_GT(Gap(physics, 3, 4), held + 0.2);
  EXPECT_LT(after.frames[7].position.z(), z_before - 0.3);
  // The front half still hangs from the static frame.
  EXPECT_NEAR(after.frames[3].position.z(), 0.525, 0.02);
}

TEST(PhysicsLocks, RemadeLockPullsThePartsBackTogether) {
  Scenario s = HangingChain();
  s.settings.gravity = Eigen::Vector3d::Zero();
  s.robots[0].modules[0].frames[0].is_static = false;
  Physics physics(s);
  const RobotState start = physics.ReadRobotState(0);
  const double joined = Gap(physics, 3, 4);
  physics.SetLockAttached("snake", "snake/lock1", false);
  // Push the back half away for 0.1 s.
  const int body = mj_name2id(physics.model(), mjOBJ_BODY, "snake/m3/f1");
  for (int i = 0; i < 50; ++i) {
    physics.mutable_data()->xfrc_applied[6 * body] = -1.0;
    physics.Step();
  }
  physics.mutable_data()->xfrc_applied[6 * body] = 0;
  physics.Step(100);
  EXPECT_GT(Gap(physics, 3, 4), joined + 0.02);
  physics.SetLockAttached("snake", "snake/lock1", true);
  EXPECT_TRUE(physics.LockStates("snake")[1].second);
  physics.Step(1000);
  EXPECT_NEAR(Gap(physics, 3, 4), joined, 1e-3);
  // The back half is rigid again: the same relative pose as at the start.
  const RobotState now = physics.ReadRobotState(0);
  const Eigen::Quaterniond rel_start =
      start.frames[3].orientation.conjugate() * start.frames[4].orientation;
  const Eigen::Quaterniond rel_now =
      now.frames[3].orientation.conjugate() * now.frames[4].orientation;
  EXPECT_LT(rel_start.angularDistance(rel_now), 0.01);
}

TEST(PhysicsLocks, BreakForceReleasesUnderLoadOnly) {
  // The middle lock carries the weight of modules 2 and 3 (0.2 kg, 1.96 N)
  // plus the bending moment of the cantilever.
  {
    Physics physics(HangingChain(4.0));
    physics.Step(1000);
    EXPECT_TRUE(physics.LockStates("snake")[1].second);
    EXPECT_LT(Gap(physics, 3, 4), 0.051);
  }
  {
    Physics physics(HangingChain(1.0));
    physics.Step(1000);
    EXPECT_FALSE(physics.LockStates("snake")[1].second);
    EXPECT_TRUE(physics.LockStates("snake")[0].second);
    EXPECT_GT(Gap(physics, 3, 4), 0.2);
  }
}

std::vector<unsigned char> Bytes(const double* v, int n) {
  const auto* p = reinterpret_cast<const unsigned char*>(v);
  return std::vector<unsigned char>(p, p + n * sizeof(double));
}

void Drive(Physics& physics, int steps) {
  std::vector<double> targets(physics.joint_count(0));
  for (int i = 0; i < steps; ++i) {
    for (size_t j = 0; j < targets.size(); ++j) {
      targets[j] = std::sin(2 * M_PI * physics.time() + 2.5 * j);
    }
    physics.SetJointTargets(0, targets);
    physics.Step();
  }
}

TEST(PhysicsLocks, CheckpointAfterAReleaseResumesBitForBit) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 6;
  options.sensor_after = {2};
  s.robots.push_back(MakeChain(options));
  Physics original(s);
  Drive(original, 300);
  original.SetLockAttached("snake", "snake/lock2", false);  // tree link
  Drive(original, 200);
  const std::string checkpoint = SaveCheckpointString(original);
  Drive(original, 300);
  auto resumed = LoadCheckpointString(checkpoint, "test");
  EXPECT_EQ(resumed->LockStates("snake"), original.LockStates("snake"));
  Drive(*resumed, 300);
  const mjModel* m = original.model();
  ASSERT_EQ(resumed->model()->nq, m->nq);
  EXPECT_EQ(Bytes(resumed->data()->qpos, m->nq),
            Bytes(original.data()->qpos, m->nq));
  EXPECT_EQ(Bytes(resumed->data()->qvel, m->nv),
            Bytes(original.data()->qvel, m->nv));
}

TEST(PhysicsLocks, ReleaseCarriesTheMotionOver) {
  // Releasing a rigid link rebuilds the model; nothing jumps.
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 4;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  Drive(physics, 300);
  const RobotState before = physics.ReadRobotState(0);
  physics.SetLockAttached("snake", "snake/lock1", false);
  const RobotState after = physics.ReadRobotState(0);
  ASSERT_EQ(before.frames.size(), after.frames.size());
  for (size_t f = 0; f < before.frames.size(); ++f) {
    EXPECT_LT((before.frames[f].position - after.frames[f].position).norm(),
              1e-12);
  }
  EXPECT_LT((before.com_velocity - after.com_velocity).norm(), 1e-9);
  for (size_t j = 0; j < before.joints.size(); ++j) {
    EXPECT_EQ(before.joints[j].angle, after.joints[j].angle);
  }
}

}  // namespace
}  // namespace mrsim
