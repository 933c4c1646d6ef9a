// Robots apart run in separate MuJoCo worlds that merge when they come
// close: each robot moves as it would alone, robots that meet collide as in
// one world, and same inputs give the same result across checkpoints.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/physics.h"
#include "sim_core/physics/scene_object_state.h"
#include "tests/common/mujoco_test.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

Robot Chain(const std::string& name, const Eigen::Vector3d& origin,
            int modules = 6) {
  ChainOptions options;
  options.name = name;
  options.modules = modules;
  options.origin = origin;
  return MakeChain(options);
}

// A travelling wave on every hinge of every robot.
void Wave(Physics& physics) {
  for (int r = 0; r < physics.robot_count(); ++r) {
    std::vector<double> targets(physics.joint_count(r));
    for (size_t j = 0; j < targets.size(); ++j) {
      targets[j] = std::sin(2 * M_PI * physics.time() / 2.0 + 1.5 * j + r);
    }
    physics.SetJointTargets(r, targets);
  }
}

// Robot `upper` lies 0.25 m above robot `lower` and falls onto it.
Scenario Falling() {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(Chain("lower", Eigen::Vector3d(0, 0, 0)));
  s.robots.push_back(Chain("upper", Eigen::Vector3d(0, 0, 0.25)));
  s.robots.push_back(Chain("far", Eigen::Vector3d(0, 3, 0)));
  return s;
}

// The same scene forced into one world: a loose part may reach any robot,
// so a scene with one runs as one world.
Scenario OneWorld(Scenario s) {
  Frame loose;
  loose.guid = "loose";
  loose.position = Eigen::Vector3d(10, 10, 0.025);
  loose.is_static = true;
  s.loose_frames.push_back(loose);
  return s;
}

double MeanZ(const RobotState& state) {
  double z = 0;
  for (const Pose& f : state.frames) z += f.position.z();
  return z / state.frames.size();
}

TEST(WorldSplit, RobotsFarApartMoveExactlyAsEachAlone) {
  Scenario both = testing::FlatScenario();
  both.robots.push_back(Chain("a", Eigen::Vector3d(0, 0, 0)));
  both.robots.push_back(Chain("b", Eigen::Vector3d(0, 2, 0)));
  Physics together(both);
  std::vector<std::unique_ptr<Physics>> alone;
  for (int r = 0; r < 2; ++r) {
    Scenario one = testing::FlatScenario();
    one.robots.push_back(both.robots[r]);
    alone.push_back(std::make_unique<Physics>(one));
  }
  for (int step = 0; step < 500; ++step) {
    Wave(together);
    together.Step();
    for (int r = 0; r < 2; ++r) {
      std::vector<double> targets = together.joint_targets(r);
      alone[r]->SetJointTargets(0, targets);
      alone[r]->Step();
    }
  }
  for (int r = 0; r < 2; ++r) {
    const RobotState split = together.ReadRobotState(r);
    const RobotState single = alone[r]->ReadRobotState(0);
    ASSERT_EQ(split.frames.size(), single.frames.size());
    for (size_t f = 0; f < split.frames.size(); ++f) {
      EXPECT_EQ(split.frames[f].position, single.frames[f].position)
          << "robot " << r << " frame " << f;
    }
    EXPECT_EQ(split.com, single.com);
  }
  // The whole scene's model and data show both robots where they are.
  const mjModel* m = together.model();
  const int body = mj_name2id(m, mjOBJ_BODY, "b/m0/f0");
  ASSERT_GE(body, 0);
  EXPECT_EQ(together.data()->xpos[3 * body + 1],
            together.ReadRobotState(1).frames[0].position.y());
}

TEST(WorldSplit, AFallingRobotLandsOnTheOtherAsInOneWorld) {
  Physics split(Falling());
  Physics one(OneWorld(Falling()));
  split.Step(500);  // 1 s: fallen and settled
  one.Step(500);
  const RobotState upper = split.ReadRobotState(1);
  // On top of the lower chain (centre 0.025 + 0.05), not through it.
  EXPECT_NEAR(MeanZ(upper), 0.075, 0.01);
  EXPECT_NEAR(MeanZ(split.ReadRobotState(0)), 0.025, 0.003);
  EXPECT_LT((upper.com - one.ReadRobotState(1).com).norm(), 0.005);
  EXPECT_LT((split.ReadRobotState(0).com - one.ReadRobotState(0).com).norm(),
            0.005);
}

TEST(WorldSplit, ARobotDrivenIntoAnotherPushesItAndNeverPassesThrough) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(Chain("a", Eigen::Vector3d(0, 0, 0)));
  // b's front frame 10 cm behind a's back frame, sliding towards it.
  s.robots.push_back(Chain("b", Eigen::Vector3d(-0.7, 0, 0)));
  Physics physics(s);
  const mjModel* m = physics.model();
  const int root = mj_name2id(m, mjOBJ_JOINT, "b/root");
  ASSERT_GE(root, 0);
  physics.mutable_data()->qvel[m->jnt_dofadr[root]] = 2.5;  // +x, m/s
  const double a_start = physics.CenterOfMass(0).x();
  double gap = 1;
  for (int step = 0; step < 400; ++step) {
    physics.Step();
    double a_back = 1e9, b_front = -1e9;
    for (const Pose& f : physics.ReadRobotState(0).frames)
      a_back = std::min(a_back, f.position.x());
    for (const Pose& f : physics.ReadRobotState(1).frames)
      b_front = std::max(b_front, f.position.x());
    gap = std::min(gap, a_back - b_front);  // centres of the facing boxes
  }
  EXPECT_GT(gap, 0.045);  // two 5 cm boxes: touching, not overlapping
  EXPECT_GT(physics.CenterOfMass(0).x() - a_start, 0.01);  // a was pushed
}

TEST(WorldSplit, ARobotDrivenIntoABallPushesIt) {
  // The ball starts in a world of its own and joins the robot's when the
  // robot reaches it.
  Scenario s = testing::FlatScenario();
  s.robots.push_back(Chain("a", Eigen::Vector3d(0, 0, 0)));
  s.robots.push_back(Chain("far", Eigen::Vector3d(0, 3, 0)));
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.1, 0.1, 0.1);  // 5 cm radius
  ball.position = Eigen::Vector3d(0.25, 0, 0.05);
  ball.mass = 0.05;
  ball.is_static = false;
  s.scene_objects.push_back(ball);
  Physics physics(s);
  const int root = mj_name2id(physics.model(), mjOBJ_JOINT, "a/root");
  ASSERT_GE(root, 0);
  physics.mutable_data()->qvel[physics.model()->jnt_dofadr[root]] = 2.0;
  physics.Step(300);
  const std::vector<SceneObjectState> objects = ReadSceneObjects(physics);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_GT(objects[0].pose.position.x(), 0.3);  // pushed along +x
  double front = -1e9;
  for (const Pose& f : physics.ReadRobotState(0).frames)
    front = std::max(front, f.position.x());
  // The robot's front box (2.5 cm half length) never went into the ball.
  EXPECT_LT(front + 0.025, objects[0].pose.position.x() - 0.05 + 0.002);
}

TEST(WorldSplit, SameInputsSameResultAcrossCheckpointsAndReset) {
  Physics first(Falling());
  Physics second(Falling());
  std::vector<unsigned char> before_merge, after_merge;
  for (int step = 0; step < 400; ++step) {
    if (step == 50) before_merge = first.SaveState();
    if (step == 250) after_merge = first.SaveState();
    Wave(first);
    first.Step();
    Wave(second);
    second.Step();
  }
  const std::vector<unsigned char> end = first.SaveState();
  EXPECT_EQ(second.SaveState(), end);
  for (const auto* saved : {&before_merge, &after_merge}) {
    Physics resumed(Falling());
    resumed.LoadState(*saved);
    while (resumed.time() < first.time() - 1e-9) {
      Wave(resumed);
      resumed.Step();
    }
    EXPECT_EQ(resumed.SaveState(), end);
  }
  // Through a checkpoint string, as mrsim-sim saves and loads.
  std::unique_ptr<Physics> loaded =
      LoadCheckpointString(SaveCheckpointString(first), "");
  EXPECT_EQ(loaded->SaveState(), end);
  // Reset after the merge: the worlds and state of a fresh build.
  first.Reset();
  EXPECT_EQ(first.SaveState(), Physics(Falling()).SaveState());
}

TEST(WorldSplit, AllRobotsInOneWorldSaveTheOneWorldFormat) {
  // Once every robot shares one world, the state is that of the whole
  // scene as one world: the format a single-world scene (or an older
  // version of the simulator) saves, which a split scene loads.
  Scenario pair = Falling();
  pair.robots.pop_back();  // lower and upper only: they merge
  Physics merged(pair);
  merged.Step(300);
  const std::vector<unsigned char> blob = merged.SaveState();
  ASSERT_GE(blob.size(), 8u);
  EXPECT_EQ(std::string(blob.begin(), blob.begin() + 7), "MRSIMST");
  Physics resumed(pair);
  resumed.LoadState(blob);
  merged.Step(100);
  resumed.Step(100);
  EXPECT_EQ(resumed.SaveState(), merged.SaveState());
}

TEST(WorldSplit, ADamagedWorldsSectionIsRefusedAndChangesNothing) {
  Physics physics(Falling());
  physics.Step(10);
  const std::vector<unsigned char> good = physics.SaveState();
  std::vector<unsigned char> bad = good;
  bad[8] = 99;  // world count
  EXPECT_THROW(physics.LoadState(bad), std::invalid_argument);
  bad = good;
  bad.resize(bad.size() - 3);
  EXPECT_THROW(physics.LoadState(bad), std::invalid_argument);
  bad = good;
  bad[16] = 7;  // the first world's robot: out of range
  EXPECT_THROW(physics.LoadState(bad), std::invalid_argument);
  EXPECT_EQ(physics.SaveState(), good);
}

}  // namespace
}  // namespace mrsim
