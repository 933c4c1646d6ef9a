#include "sim_core/physics/physics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/scenario/terrain.h"
#include "tests/common/child_process.h"
#include "tests/common/mujoco_test.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

TEST(PhysicsServo, HingeReachesTargetWithoutExceedingMaxVel) {
  Scenario s = testing::FlatScenario();
  const double max_vel = 2.0;
  s.robots.push_back(testing::CantileverModule(
      "arm", Eigen::Vector3d(0, 0, 0.5), Axis::kYaw, 10.0, max_vel, 1.2));
  Physics physics(s);
  ASSERT_EQ(physics.joint_count(0), 1);
  physics.SetJointTargets(0, {1.0});
  double fastest = 0;
  for (int i = 0; i < 1000; ++i) {  // 2 s
    physics.Step();
    const double speed = physics.ReadRobotState(0).joints[0].speed;
    fastest = std::max(fastest, std::abs(speed));
    ASSERT_LE(std::abs(speed), max_vel) << "step " << i;
  }
  // It moved at (nearly) full speed, then settled on the target.
  EXPECT_GT(fastest, 0.9 * max_vel);
  const JointState joint = physics.ReadRobotState(0).joints[0];
  EXPECT_NEAR(joint.angle, 1.0, 0.01);
  EXPECT_NEAR(joint.speed, 0.0, 0.01);
}

TEST(PhysicsServo, VelocityGainAndMaxTorqueComeFromTheJoint) {
  // First step from rest towards a far target: commanded speed = max_vel
  // (2 rad/s), so the torque is velocity_gain * 2 unless max_torque caps it.
  auto first_torque = [](double gain, double max_torque) {
    Scenario s = testing::FlatScenario();
    Robot arm = testing::CantileverModule("arm", Eigen::Vector3d(0, 0, 0.5),
                                          Axis::kYaw, 10.0, 2.0, 1.2);
    arm.modules[0].joint.velocity_gain = gain;
    arm.modules[0].joint.max_torque = max_torque;
    s.robots.push_back(arm);
    Physics physics(s);
    physics.SetJointTargets(0, {1.0});
    physics.Step();
    return physics.ReadRobotState(0).joints[0].torque;
  };
  EXPECT_DOUBLE_EQ(first_torque(0.5, 5.0), 1.0);
  EXPECT_DOUBLE_EQ(first_torque(3.0, 5.0), 5.0);
  EXPECT_DOUBLE_EQ(first_torque(3.0, 0.25), 0.25);
}

TEST(PhysicsServo, HingeNeverExceedsItsTorqueLimit) {
  // A pitch snake lifting its body against gravity with weak servos, each
  // hinge its own limit: every step, every torque within its limit, and
  // every servo saturates at some point (so the limit is what held it).
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 6;
  Robot robot = MakeChain(options);
  std::vector<double> limits;
  for (size_t i = 0; i < robot.modules.size(); ++i) {
    robot.modules[i].joint.max_torque = 0.05 + 0.03 * i;
    robot.modules[i].joint.velocity_gain = 20.0;
    limits.push_back(robot.modules[i].joint.max_torque);
  }
  s.robots.push_back(robot);
  Physics physics(s);
  std::vector<double> peak(limits.size(), 0.0);
  std::vector<double> targets(limits.size());
  for (int i = 0; i < 2000; ++i) {
    for (size_t j = 0; j < targets.size(); ++j) {
      targets[j] = 1.5 * std::sin(2 * M_PI * physics.time() / 2.0 + 2.5 * j);
    }
    physics.SetJointTargets(0, targets);
    physics.Step();
    const RobotState st = physics.ReadRobotState(0);
    for (size_t j = 0; j < limits.size(); ++j) {
      ASSERT_LE(std::abs(st.joints[j].torque), limits[j])
          << "hinge " << j << " at step " << i;
      peak[j] = std::max(peak[j], std::abs(st.joints[j].torque));
    }
  }
  for (size_t j = 0; j < limits.size(); ++j) {
    EXPECT_DOUBLE_EQ(peak[j], limits[j]) << "hinge " << j;
  }
}

TEST(PhysicsServo, PitchHingeHoldsTargetUnderGravity) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(testing::CantileverModule(
      "arm", Eigen::Vector3d(0, 0, 0.5), Axis::kPitch, 10.0, 3.0, 1.5));
  Physics physics(s);
  physics.SetJointTargets(0, {0.5});
  physics.Step(1000);
  const RobotState state = physics.ReadRobotState(0);
  EXPECT_NEAR(state.joints[0].angle, 0.5, 0.01);
  // The servo carries the arm's weight: torque about the hinge is m g r.
  const double lever = 0.025 * std::cos(0.5);
  EXPECT_NEAR(std::abs(state.joints[0].torque), 0.05 * 9.81 * lever, 0.002);
  // A positive angle turns frame 1 (on the -x side) about +y: upwards.
  EXPECT_GT(state.frames[1].position.z(), 0.5);
}

TEST(PhysicsServo, TargetsAreClampedToTheRange) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(testing::CantileverModule(
      "arm", Eigen::Vector3d(0, 0, 0.5), Axis::kYaw, 10.0, 3.0, 0.8));
  Physics physics(s);
  physics.SetJointTargets(0, {2.0});
  EXPECT_DOUBLE_EQ(physics.joint_targets(0)[0], 0.8);
  physics.Step(1000);
  EXPECT_NEAR(physics.ReadRobotState(0).joints[0].angle, 0.8, 0.01);
  EXPECT_THROW(physics.SetJointTargets(0, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(physics.SetJointTargets(0, {NAN}), std::invalid_argument);
}

TEST(PhysicsLocks, LockedPartsHoldUnderLoad) {
  // A chain of 3 modules with a sensor module in the middle, hanging
  // sideways from a static first frame: gravity loads every lock.
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 3;
  options.pattern = ChainPattern::kYaw;
  options.sensor_after = {0};
  options.origin = Eigen::Vector3d(0, 0, 0.5);
  Robot robot = MakeChain(options);
  robot.modules[0].frames[0].is_static = true;
  // A heavy load at the far end.
  robot.modules[2].frames[1].mass = 0.5;
  s.robots.push_back(robot);
  Physics physics(s);
  const RobotState before = physics.ReadRobotState(0);
  physics.Step(1000);
  const RobotState after = physics.ReadRobotState(0);
  // Locked pairs keep their relative pose: m0/f1 - sm0 - m1/f0, m1/f1 - m2/f0.
  auto relative = [](const Pose& a, const Pose& b) {
    return Eigen::Vector3d(a.orientation.conjugate() *
                           (b.position - a.position));
  };
  const Pose& sm_before = before.sensor_modules[0].pose;
  const Pose& sm_after = after.sensor_modules[0].pose;
  EXPECT_LT((relative(before.frames[1], sm_before) -
             relative(after.frames[1], sm_after))
                .norm(),
            1e-9);
  EXPECT_LT((relative(sm_before, before.frames[2]) -
             relative(sm_after, after.frames[2]))
                .norm(),
            1e-9);
  EXPECT_LT((relative(before.frames[3], before.frames[4]) -
             relative(after.frames[3], after.frames[4]))
                .norm(),
            1e-9);
  // The hinges hold the chain straight (yaw servos, gravity across them
  // loads the locks and the joint constraints, not the servos).
  for (const JointState& j : after.joints) EXPECT_NEAR(j.angle, 0.0, 0.01);
}

TEST(PhysicsLocks, LoopClosingLockHoldsUnderLoad) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 2;
  options.origin = Eigen::Vector3d(0, 0, 0.5);
  Robot robot = MakeChain(options);
  robot.modules[0].frames[0].is_static = true;
  robot.modules[1].frames[1].mass = 0.5;
  Joint loop;
  loop.guid = "loop";
  loop.type = JointType::kLock;
  loop.left_frame_guid = robot.modules[0].frames[1].guid;
  loop.right_frame_guid = robot.modules[1].frames[1].guid;
  robot.locks.push_back(loop);
  s.robots.push_back(robot);
  Physics physics(s);
  const RobotState before = physics.ReadRobotState(0);
  physics.Step(1000);
  const RobotState after = physics.ReadRobotState(0);
  // m1/f1 keeps its place relative to m0/f1 (the welded pair), so the
  // hinge of module 1 inside the loop cannot bend.
  auto relative = [](const Pose& a, const Pose& b) {
    return Eigen::Vector3d(a.orientation.conjugate() *
                           (b.position - a.position));
  };
  EXPECT_LT((relative(before.frames[1], before.frames[3]) -
             relative(after.frames[1], after.frames[3]))
                .norm(),
            2e-4);
  EXPECT_NEAR(after.joints[1].angle, 0.0, 0.005);
}

TEST(PhysicsTerrain, BoxRestsAtTheImageHeight) {
  const std::string dir = testing::TempDir("physics_terrain");
  // 20x20 px at 0.05 m: a plateau of grey 200 in the middle of a 50 slope.
  testing::WriteGreyPng(dir + "/plateau.png", 20, 20, [](int r, int c) {
    return (r >= 6 && r < 14 && c >= 6 && c < 14) ? 200 : 50 + 5 * (c % 3);
  });
  Scenario s = testing::FlatScenario();
  s.base_dir = dir;
  s.scene.height_image = "plateau.png";
  s.scene.height = 0.4;
  s.scene.meters_per_pixel = 0.05;
  s.scene.position = Eigen::Vector3d(-0.5, -0.5, 0.1);
  SceneObject box;
  box.guid = "box";
  box.size = Eigen::Vector3d(0.1, 0.1, 0.1);
  box.position = Eigen::Vector3d(0, 0, 1.0);
  box.mass = 0.2;
  s.scene_objects.push_back(box);
  Physics physics(s);
  physics.Step(1000);
  const mjModel* m = physics.model();
  const int body = mj_name2id(m, mjOBJ_BODY, "scene/obj0");
  const double z = physics.data()->xpos[3 * body + 2];
  // Darkest pixel 50 -> 0, brightest 200 -> height.
  const TerrainImage image = LoadTerrainImage(s.scene, dir);
  const double plateau = s.scene.position.z() + s.scene.height;
  EXPECT_NEAR(TerrainHeightAt(s.scene, image, 0, 0), s.scene.height, 1e-6);
  EXPECT_NEAR(z, plateau + 0.05, 0.003);
  EXPECT_NEAR(physics.data()->xpos[3 * body], 0.0, 0.01);
}

TEST(PhysicsState, ReadsPosesComAndIndices) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 4;
  options.pattern = ChainPattern::kPitchYaw;
  options.sensor_after = {1};
  s.robots.push_back(MakeChain(options));
  options.name = "second";
  options.origin = Eigen::Vector3d(0, 1, 0);
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  ASSERT_EQ(physics.robot_count(), 2);
  EXPECT_EQ(physics.robot_index("second"), 1);
  EXPECT_EQ(physics.robot_index("nobody"), -1);
  EXPECT_EQ(physics.joint_count(1), 4);
  EXPECT_EQ(physics.joint_axis(0, 1), Axis::kYaw);
  const RobotState state = physics.ReadRobotState(1);
  EXPECT_EQ(state.robot, "second");
  ASSERT_EQ(state.frames.size(), 8u);
  ASSERT_EQ(state.modules.size(), 4u);
  ASSERT_EQ(state.sensor_modules.size(), 1u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_LT(
        (state.modules[i].position - s.robots[1].modules[i].position).norm(),
        1e-9);
    EXPECT_LT((state.joints[i].world.position - s.robots[1].modules[i].position)
                  .norm(),
              1e-9);
  }
  // CoM = mass-weighted mean of the parts (frames 0.05 kg, sensor module).
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0;
  for (const Module& m : s.robots[1].modules) {
    for (const Frame& f : m.frames) {
      sum += f.mass * f.position;
      mass += f.mass;
    }
  }
  const SensorModule& sm = s.robots[1].sensor_modules[0];
  sum += sm.mass * sm.position;
  mass += sm.mass;
  EXPECT_LT((state.com - sum / mass).norm(), 1e-9);
  EXPECT_LT((physics.CenterOfMass(1) - sum / mass).norm(), 1e-9);
  EXPECT_LT(state.com_velocity.norm(), 1e-9);
  EXPECT_THROW(physics.ReadRobotState(2), std::out_of_range);
}

TEST(PhysicsState, SaveLoadStateContinuesBitForBit) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 5;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  auto drive = [](Physics& p, int steps) {
    std::vector<double> targets(p.joint_count(0));
    for (int i = 0; i < steps; ++i) {
      for (size_t j = 0; j < targets.size(); ++j) {
        targets[j] = std::sin(2 * M_PI * p.time() / 2 + j);
      }
      p.SetJointTargets(0, targets);
      p.Step();
    }
  };
  drive(physics, 300);
  const std::vector<unsigned char> saved = physics.SaveState();
  drive(physics, 300);
  const std::vector<unsigned char> a = physics.SaveState();
  Physics other(s);
  other.LoadState(saved);
  drive(other, 300);
  EXPECT_EQ(other.SaveState(), a);
  physics.Reset();
  EXPECT_EQ(physics.time(), 0.0);
  EXPECT_EQ(physics.joint_targets(0), std::vector<double>(5, 0.0));
  std::vector<unsigned char> broken = saved;
  broken.resize(broken.size() - 8);
  EXPECT_THROW(other.LoadState(broken), std::invalid_argument);
}

TEST(PhysicsInstability, NonFiniteStateRaisesPhysicsError) {
  Scenario s = testing::FlatScenario();
  ChainOptions options;
  options.modules = 3;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  physics.Step(10);
  physics.mutable_data()->qvel[6] = NAN;  // module 0's hinge
  testing::ExpectMujocoWarnings expected;
  try {
    physics.Step();
    FAIL() << "expected PhysicsError";
  } catch (const PhysicsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("t=0.0200"), std::string::npos) << what;
    // NaN speed becomes NaN position when integrated; either is named.
    EXPECT_TRUE(what.find("BADQVEL") != std::string::npos ||
                what.find("BADQPOS") != std::string::npos)
        << what;
    EXPECT_NE(what.find("snake/m0/f1"), std::string::npos) << what;
  }
  // After a reset it runs again.
  physics.Reset();
  EXPECT_NO_THROW(physics.Step(10));
}

TEST(PhysicsInstability, ExplodingModelRaisesPhysicsError) {
  // A far too large timestep for a stiff, light chain on the ground.
  Scenario s = testing::FlatScenario();
  s.settings.timestep = 0.2;
  ChainOptions options;
  options.modules = 4;
  options.module_mass = 0.001;
  options.kp = 1000;
  options.max_vel = 100;
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  std::vector<double> targets(4);
  testing::ExpectMujocoWarnings expected;
  EXPECT_THROW(
      {
        for (int i = 0; i < 2000; ++i) {
          for (int j = 0; j < 4; ++j) targets[j] = (i + j) % 2 ? 1.5 : -1.5;
          physics.SetJointTargets(0, targets);
          physics.Step();
        }
      },
      PhysicsError);
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

TEST(PhysicsLooseParts, LooseFramesAndJointsAreSimulated) {
  Scenario s = testing::FlatScenario();
  for (int f = 0; f < 2; ++f) {
    Frame frame;
    frame.guid = "loose" + std::to_string(f);
    frame.position = Eigen::Vector3d(0.025 - 0.05 * f, 0, 0.3);
    s.loose_frames.push_back(frame);
  }
  Joint hinge;
  hinge.guid = "free hinge";
  hinge.left_frame_guid = "loose0";
  hinge.right_frame_guid = "loose1";
  s.loose_joints.push_back(hinge);
  Physics physics(s);
  EXPECT_EQ(physics.robot_count(), 0);
  const mjModel* m = physics.model();
  const int body = mj_name2id(m, mjOBJ_BODY, "loose/f1");
  ASSERT_GE(body, 0);
  EXPECT_EQ(m->nu, 0);
  physics.Step(500);
  // They fell onto the ground.
  EXPECT_NEAR(physics.data()->xpos[3 * body + 2], 0.025, 0.005);
}

// Loose parts read as a robot's state under the owner "loose": where they
// are after the physics moved them, not where the scenario put them.
TEST(PhysicsLooseParts, LooseStateIsWhereThePhysicsMovedThem) {
  Scenario s = testing::FlatScenario();
  for (int f = 0; f < 2; ++f) {
    Frame frame;
    frame.guid = "loose" + std::to_string(f);
    frame.position = Eigen::Vector3d(0.025 - 0.05 * f, 1.0, 0.3);
    s.loose_frames.push_back(frame);
  }
  Joint hinge;
  hinge.guid = "free hinge";
  hinge.left_frame_guid = "loose0";
  hinge.right_frame_guid = "loose1";
  s.loose_joints.push_back(hinge);
  SensorModule eye;
  eye.guid = "eye";
  eye.position = Eigen::Vector3d(0, -1.0, 0.2);
  eye.imu = Imu{};
  DistanceSensor ray;
  ray.sensor_position = 0;
  eye.distance_sensors.push_back(ray);
  s.loose_sensor_modules.push_back(eye);
  Physics physics(s);
  ASSERT_TRUE(physics.has_loose_parts());

  const RobotState start = physics.ReadLooseState();
  EXPECT_EQ(start.robot, kLooseOwnerName);
  ASSERT_EQ(start.frames.size(), 2u);  // one per loose frame
  EXPECT_TRUE(start.modules.empty());
  ASSERT_EQ(start.joints.size(), 1u);
  ASSERT_EQ(start.sensor_modules.size(), 1u);
  EXPECT_NEAR(start.frames[1].position.x(), -0.025, 1e-9);
  EXPECT_NEAR(start.frames[1].position.z(), 0.3, 1e-9);
  EXPECT_NEAR(start.sensor_modules[0].pose.position.z(), 0.2, 1e-9);

  physics.Step(1000);  // 2 s: they fell and came to rest
  const RobotState rest = physics.ReadLooseState();
  EXPECT_NEAR(rest.frames[1].position.z(), 0.025, 0.005);
  EXPECT_NEAR(rest.sensor_modules[0].pose.position.z(), 0.025, 0.005);
  EXPECT_NEAR(rest.time, physics.time(), 1e-12);
  EXPECT_EQ(rest.joints[0].torque, 0.0);  // no servo
  EXPECT_TRUE(std::isfinite(rest.joints[0].angle));
  EXPECT_LT(rest.com.z(), 0.05);
  // The readings are the module's: one distance, the IMU at rest reads
  // gravity along its up axis.
  ASSERT_EQ(rest.sensor_modules[0].distances.size(), 1u);
  EXPECT_GT(rest.sensor_modules[0].distances[0], 0.0);
  ASSERT_EQ(rest.sensor_modules[0].readings.size(), 1u);
  EXPECT_EQ(rest.sensor_modules[0].readings[0].kind, "imu");
  EXPECT_NEAR(rest.sensor_modules[0].readings[0].values[2], 9.81, 0.2);

  Physics none(testing::FlatScenario());
  EXPECT_FALSE(none.has_loose_parts());
  EXPECT_THROW(none.ReadLooseState(), std::logic_error);
}

// A static base in the air with an arm on each side, each on a loose hinge
// about the vertical (gravity turns neither): the +x arm's hinge has a
// servo when `servo`, the -x arm's never.
Scenario LooseArms(bool servo) {
  Scenario s = testing::FlatScenario();
  const Eigen::Quaterniond up(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));  // y -> z
  for (const auto& [guid, x] :
       {std::make_pair("base", 0.0), std::make_pair("driven arm", 0.05),
        std::make_pair("free arm", -0.05)}) {
    Frame frame;
    frame.guid = guid;
    frame.position = Eigen::Vector3d(x, 0, 0.3);
    frame.quat_rotation = up;
    frame.is_static = frame.guid == "base";
    s.loose_frames.push_back(frame);
  }
  for (const char* arm : {"driven arm", "free arm"}) {
    Joint hinge;
    hinge.guid = std::string(arm) + " hinge";
    hinge.left_frame_guid = "base";
    hinge.right_frame_guid = arm;
    hinge.servo = servo && hinge.guid == "driven arm hinge";
    s.loose_joints.push_back(hinge);
  }
  return s;
}

// A loose hinge with <servo> is driven to the angle commanded, as a
// module's hinge is; a passive one beside it, under the same physics, does
// not move.
TEST(PhysicsLooseParts, AServoedLooseHingeReachesItsTargetAPassiveOneStays) {
  Physics physics(LooseArms(true));
  ASSERT_EQ(physics.loose_servo_count(), 1);
  EXPECT_EQ(physics.model()->nu, 1);
  EXPECT_EQ(physics.loose_targets(), std::vector<double>{0.0});
  physics.SetLooseTargets({0.5});
  physics.Step(1000);  // 2 s
  const RobotState state = physics.ReadLooseState();
  ASSERT_EQ(state.joints.size(), 2u);  // both hinges, in scenario order
  EXPECT_NEAR(state.joints[0].angle, 0.5, 0.01);
  EXPECT_NEAR(state.joints[1].angle, 0.0, 1e-3);
  EXPECT_EQ(state.joints[1].torque, 0.0);  // passive: no actuator

  // Clamped to its limits; a wrong count or a NaN is refused.
  physics.SetLooseTargets({3.0});
  EXPECT_EQ(physics.loose_targets(), std::vector<double>{1.5708});
  EXPECT_THROW(physics.SetLooseTargets({0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(physics.SetLooseTargets({std::nan("")}), std::invalid_argument);

  // A checkpoint keeps the loose targets; a reset zeroes them.
  physics.SetLooseTargets({-0.4});
  const std::vector<unsigned char> saved = physics.SaveState();
  Physics resumed(LooseArms(true));
  resumed.LoadState(saved);
  EXPECT_EQ(resumed.loose_targets(), std::vector<double>{-0.4});
  resumed.Reset();
  EXPECT_EQ(resumed.loose_targets(), std::vector<double>{0.0});
}

TEST(PhysicsLooseParts, WithoutServoTheLooseHingesArePassive) {
  Physics physics(LooseArms(false));
  EXPECT_EQ(physics.loose_servo_count(), 0);
  EXPECT_EQ(physics.model()->nu, 0);
  EXPECT_THROW(physics.SetLooseTargets({0.5}), std::invalid_argument);
  EXPECT_NO_THROW(physics.SetLooseTargets({}));
  physics.Step(1000);
  const RobotState state = physics.ReadLooseState();
  ASSERT_EQ(state.joints.size(), 2u);
  EXPECT_NEAR(state.joints[0].angle, 0.0, 1e-3);
  EXPECT_NEAR(state.joints[1].angle, 0.0, 1e-3);
}

// A loose frame welded beside a static one 1 m up by a loose lock of the
// given break force; without the lock it would fall.
Scenario HangingLooseFrame(double break_force) {
  Scenario s = testing::FlatScenario();
  for (const auto& [guid, x] :
       {std::make_pair("post", 0.0), std::make_pair("door", 0.06)}) {
    Frame frame;
    frame.guid = guid;
    frame.position = Eigen::Vector3d(x, 0, 1.0);
    frame.is_static = frame.guid == "post";
    s.loose_frames.push_back(frame);
  }
  Joint lock;
  lock.guid = "weld";
  lock.left_frame_guid = "post";
  lock.right_frame_guid = "door";
  lock.type = JointType::kLock;
  lock.break_force = break_force;
  s.loose_joints.push_back(lock);
  return s;
}

// A loose lock breaks at its breakForce as a robot's lock does: a weak one
// gives way under the hanging frame's weight and the frame falls; a strong
// one, or 0 (never breaks), holds it.
TEST(PhysicsLooseParts, ALooseLockBreaksAtItsBreakForce) {
  Physics weak(HangingLooseFrame(0.001));
  using LockStates = std::vector<std::pair<std::string, bool>>;
  EXPECT_EQ(weak.LockStates(kLooseOwnerName), (LockStates{{"weld", true}}));
  weak.Step(1000);  // 2 s
  EXPECT_NEAR(weak.ReadLooseState().frames[1].position.z(), 0.025, 0.005);
  EXPECT_EQ(weak.LockStates(kLooseOwnerName), (LockStates{{"weld", false}}));

  for (double strong : {1000.0, 0.0}) {
    SCOPED_TRACE(strong);
    Physics held(HangingLooseFrame(strong));
    held.Step(1000);
    EXPECT_NEAR(held.ReadLooseState().frames[1].position.z(), 1.0, 0.01);
    EXPECT_EQ(held.LockStates(kLooseOwnerName), (LockStates{{"weld", true}}));
  }
}

// A checkpoint keeps a broken loose lock broken.
TEST(PhysicsLooseParts, ACheckpointKeepsABrokenLooseLockBroken) {
  Physics physics(HangingLooseFrame(0.001));
  physics.Step(50);
  ASSERT_FALSE(physics.LockStates(kLooseOwnerName)[0].second);
  Physics resumed(HangingLooseFrame(0.001));
  resumed.LoadState(physics.SaveState());
  EXPECT_FALSE(resumed.LockStates(kLooseOwnerName)[0].second);
  physics.Step(500);
  resumed.Step(500);
  EXPECT_EQ(resumed.ReadLooseState().frames[1].position.z(),
            physics.ReadLooseState().frames[1].position.z());
}

TEST(PhysicsExamples, ExampleScenariosRun) {
  for (const char* name : {"snake11.xml", "case_study.xml", "terrain.xml"}) {
    SCOPED_TRACE(name);
    const std::string path =
        testing::SourcePath(std::string("scenarios/") + name);
    ASSERT_TRUE(std::ifstream(path).good()) << path;
    Physics physics(ReadScenarioFile(path));
    ASSERT_GE(physics.robot_count(), 1);
    std::vector<double> targets(physics.joint_count(0));
    for (int i = 0; i < 500; ++i) {
      for (size_t j = 0; j < targets.size(); ++j) {
        targets[j] = std::sin(2 * M_PI * physics.time() / 2 + 2.5 * j);
      }
      physics.SetJointTargets(0, targets);
      physics.Step();
    }
    const RobotState state = physics.ReadRobotState(0);
    EXPECT_TRUE(state.com.allFinite());
    for (const SensorModuleState& sm : state.sensor_modules) {
      for (double d : sm.distances) EXPECT_GT(d, 0);
    }
  }
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

TEST(PhysicsState, ComVelocityOfAFallingRobot) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(
      testing::SensorModuleRobot("faller", Eigen::Vector3d(0, 0, 2.0)));
  Physics physics(s);
  physics.Step(100);  // 0.2 s of free fall
  const RobotState state = physics.ReadRobotState(0);
  // Semi-implicit Euler: v = -g n dt exactly, z = z0 - g dt^2 n (n+1) / 2.
  EXPECT_NEAR(state.com_velocity.z(), -9.81 * 0.2, 1e-9);
  EXPECT_NEAR(state.com.z(), 2.0 - 9.81 * 0.002 * 0.002 * 100 * 101 / 2, 1e-9);
  EXPECT_NEAR(state.time, 0.2, 1e-12);
}

}  // namespace
}  // namespace mrsim
