// Contact and constraint-row buffers: sized for the model at rest, grown
// when a step needs more, never a constraint dropped (MuJoCo 2.2's
// CONTACTFULL / CNSTRFULL warnings mean it dropped some).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_handlers.h"
#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/physics/physics.h"
#include "tests/common/mujoco_test.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

// Twelve 10 cm boxes overlapping in one spot: every pair touches, far more
// contacts than twelve boxes resting on the ground make.
Scenario Heap() {
  Scenario s = testing::FlatScenario();
  for (int i = 0; i < 12; ++i) {
    SceneObject box;
    box.guid = "box" + std::to_string(i);
    box.position = Eigen::Vector3d(0.01 * i, 0.005 * i, 0.06 + 0.015 * i);
    box.quat_rotation = Eigen::Quaterniond(
        Eigen::AngleAxisd(0.25 * i, Eigen::Vector3d::UnitZ()));
    s.scene_objects.push_back(box);
  }
  return s;
}

// Contacts and constraint rows MuJoCo finds for the current state with
// buffers far larger than it needs.
std::pair<int, int> FoundWithRoomToSpare(const Physics& physics) {
  MjModelPtr m(mj_copyModel(nullptr, physics.model()));
  m->nconmax += 100;
  m->njmax += 400;
  MjDataPtr d(mj_makeData(m.get()));
  mju_copy(d->qpos, physics.data()->qpos, m->nq);
  mju_copy(d->qvel, physics.data()->qvel, m->nv);
  mj_fwdPosition(m.get(), d.get());
  EXPECT_EQ(d->warning[mjWARN_CONTACTFULL].number, 0);
  EXPECT_EQ(d->warning[mjWARN_CNSTRFULL].number, 0);
  return {d->ncon, d->nefc};
}

TEST(PhysicsConstraintRoom, AHeapBeyondTheRestingSizeDropsNoConstraint) {
  const Scenario heap = Heap();
  const MjModelPtr at_rest = CompileScenarioModel(heap, MjcfOptions{});
  testing::ExpectMujocoWarnings overflow;  // MuJoCo says so, Physics copes
  Physics physics(heap);
  for (int step = 0; step <= 20; ++step) {
    if (step % 10 == 0) {
      const auto [ncon, nefc] = FoundWithRoomToSpare(physics);
      ASSERT_EQ(physics.data()->ncon, ncon) << "step " << step;
      ASSERT_EQ(physics.data()->nefc, nefc) << "step " << step;
    }
    ASSERT_EQ(physics.data()->warning[mjWARN_CONTACTFULL].number, 0);
    ASSERT_EQ(physics.data()->warning[mjWARN_CNSTRFULL].number, 0);
    physics.Step();
  }
  EXPECT_GE(overflow.count(), 1);
  // The heap needed more than the resting size, so the buffers grew.
  EXPECT_GT(physics.model()->nconmax, at_rest->nconmax);
  EXPECT_GT(physics.model()->njmax, at_rest->njmax);
}

TEST(PhysicsConstraintRoom, GrowingTheBuffersChangesNoResult) {
  // The same heap stepped twice: once growing on the way, once after a
  // Reset() with the grown buffers from the start.
  testing::ExpectMujocoWarnings overflow;
  Physics physics(Heap());
  physics.Step(100);
  const std::vector<unsigned char> grown_on_the_way = physics.SaveState();
  physics.Reset();
  physics.Step(100);
  EXPECT_EQ(physics.SaveState(), grown_on_the_way);
}

TEST(PhysicsConstraintRoom, ChainsAndCrowdsAtRestNeverOverflow) {
  // Fails on MuJoCo's overflow warning: the resting sizes hold a long chain
  // and a crowd lying on the ground, and what the first steps bring.
  Scenario crowd = testing::FlatScenario();
  ChainOptions long_chain;
  long_chain.modules = 100;
  long_chain.pattern = ChainPattern::kPitchYaw;
  crowd.robots.push_back(MakeChain(long_chain));
  for (int i = 0; i < 5; ++i) {
    ChainOptions snake;
    snake.name = "snake" + std::to_string(i);
    snake.origin = Eigen::Vector3d(0, 0.3 * (i + 1), 0);
    crowd.robots.push_back(MakeChain(snake));
  }
  const long warnings_before = MujocoWarningCount();
  Physics physics(crowd);
  physics.Step(20);
  EXPECT_EQ(MujocoWarningCount(), warnings_before) << LastMujocoWarning();
  // The robots lie apart, so each runs in a world of its own
  // (docs/physics.md, "Separate worlds"): every part rests on the ground.
  for (int r = 0; r < physics.robot_count(); ++r) {
    for (const Pose& frame : physics.ReadRobotState(r).frames) {
      EXPECT_NEAR(frame.position.z(), 0.025, 0.003) << physics.robot_name(r);
    }
  }
  // The long chain alone: one world, sized at rest, all its boxes flat.
  Scenario chain = testing::FlatScenario();
  chain.robots.push_back(MakeChain(long_chain));
  Physics alone(chain);
  const MjModelPtr chain_at_rest = CompileScenarioModel(chain, MjcfOptions{});
  alone.Step(20);
  EXPECT_EQ(MujocoWarningCount(), warnings_before) << LastMujocoWarning();
  EXPECT_EQ(alone.model()->njmax, chain_at_rest->njmax);
  // Each colliding box (the end frames, one per flush locked pair of
  // frames, two where a weld cuts the chain for nesting) touches down at
  // its four corners.
  const int boxes = testing::CollidingRobotGeoms(alone.model());
  EXPECT_LT(boxes, 200);
  EXPECT_EQ(alone.data()->ncon, 4 * boxes);
}

}  // namespace
}  // namespace mrsim
