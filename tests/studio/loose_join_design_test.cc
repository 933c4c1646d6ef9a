// Joining loose parts the user picks, and moving them on the ground, in the
// studio's editing model without a window (REQ-1.3.4): a loose sensor
// module locked to a loose frame rides on it in the physics, a hinge joins
// two loose frames, a joint that would join nothing new is refused, and a
// loose part dragged on the ground takes the parts joined to it along.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_validate.h"
#include "studio/design/design.h"
#include "studio/design/ground_move.h"

namespace mrsim::studio {
namespace {

using ::testing::HasSubstr;

// A one-module snake, a loose frame and a loose sensor module beside it.
Design SnakeFrameAndSensorModule() {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  d.AddLoose(LoosePart::kFrame);
  d.AddLoose(LoosePart::kSensorModule);
  return d;
}

std::vector<std::string> Guids(const std::vector<LockEnd>& ends) {
  std::vector<std::string> out;
  for (const LockEnd& e : ends) out.push_back(e.guid);
  return out;
}

TEST(StudioLooseJoin, TheLoosePartsAreOfferedByNameUntilJoined) {
  Design d = SnakeFrameAndSensorModule();
  const std::string frame = d.scenario().loose_frames.at(0).guid;
  const std::string sm = d.scenario().loose_sensor_modules.at(0).guid;
  const std::vector<LockEnd> ends = d.LooseEnds();
  ASSERT_EQ(Guids(ends), (std::vector<std::string>{frame, sm}));
  EXPECT_EQ(ends[0].name, "loose frame " + frame);
  EXPECT_EQ(ends[1].name, "loose sensor module " + sm);
  // The robot's parts are not loose: a loose joint cannot reach them.
  EXPECT_EQ(Guids(d.LooseJoinableTo(sm)), std::vector<std::string>{frame});

  d.JoinLoose(sm, frame, JointType::kLock);
  EXPECT_TRUE(d.LooseJoinableTo(sm).empty());
  EXPECT_TRUE(d.LooseJoinableTo(frame).empty());
}

TEST(StudioLooseJoin, ALooseSensorModuleLockedToALooseFrameRidesOnIt) {
  Design d = SnakeFrameAndSensorModule();
  const std::string frame = d.scenario().loose_frames.at(0).guid;
  const std::string sm = d.scenario().loose_sensor_modules.at(0).guid;
  d.JoinLoose(sm, frame, JointType::kLock);
  ASSERT_EQ(d.scenario().loose_joints.size(), 1u);
  const Joint& lock = d.scenario().loose_joints[0];
  EXPECT_EQ(lock.type, JointType::kLock);
  EXPECT_EQ(lock.left_frame_guid, sm);
  EXPECT_EQ(lock.right_frame_guid, frame);
  EXPECT_EQ(d.selection(), (Selection{SelectionKind::kLooseJoint, 0, 0}));
  EXPECT_NO_THROW(ValidateScenario(d.scenario()));

  // Lifted 0.2 m and dropped, the two fall and land as one body: the
  // distance between them is the design's.
  Scenario s = d.scenario();
  s.loose_frames[0].position.z() += 0.2;
  s.loose_sensor_modules[0].position.z() += 0.2;
  const double apart =
      (s.loose_frames[0].position - s.loose_sensor_modules[0].position).norm();
  Physics physics(s);
  physics.Step(1000);
  const RobotState rest = physics.ReadLooseState();
  ASSERT_EQ(rest.frames.size(), 1u);
  ASSERT_EQ(rest.sensor_modules.size(), 1u);
  EXPECT_LT(rest.frames[0].position.z(), 0.1);  // it fell
  EXPECT_NEAR(
      (rest.frames[0].position - rest.sensor_modules[0].pose.position).norm(),
      apart, 1e-3);

  // Selected, the lock takes a breaking force as a robot's lock does.
  d.SetField({d.selection(), "", "breakForce"}, "40");
  EXPECT_EQ(d.scenario().loose_joints[0].break_force, 40);
  d.Undo();
  d.Undo();
  EXPECT_TRUE(d.scenario().loose_joints.empty());
}

TEST(StudioLooseJoin, TwoLooseFramesJoinedByAHingeTurnAboutIt) {
  Design d;
  d.AddLoose(LoosePart::kFrame);
  d.AddLoose(LoosePart::kFrame);
  const std::string a = d.scenario().loose_frames.at(0).guid;
  const std::string b = d.scenario().loose_frames.at(1).guid;
  d.JoinLoose(a, b, JointType::kHinge);
  ASSERT_EQ(d.scenario().loose_joints.size(), 1u);
  EXPECT_EQ(d.scenario().loose_joints[0].type, JointType::kHinge);
  Physics physics(d.scenario());
  const RobotState state = physics.ReadLooseState();
  EXPECT_EQ(state.joints.size(), 1u);  // a hinge, passive until its servo
}

TEST(StudioLooseJoin, AJointThatJoinsNothingNewIsRefusedSayingWhy) {
  Design d = SnakeFrameAndSensorModule();
  const std::string frame = d.scenario().loose_frames.at(0).guid;
  const std::string sm = d.scenario().loose_sensor_modules.at(0).guid;
  const std::string robot_frame =
      d.scenario().robots.at(0).modules.at(0).frames[0].guid;
  const Scenario before = d.scenario();
  try {
    d.JoinLoose(sm, sm, JointType::kLock);
    FAIL() << "a part joined to itself";
  } catch (const DesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("two different parts"));
  }
  try {
    d.JoinLoose(sm, robot_frame, JointType::kLock);
    FAIL() << "a loose joint to a robot's frame";
  } catch (const DesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("loose frames or loose sensor modules"));
  }
  EXPECT_EQ(d.scenario().loose_joints, before.loose_joints);
  d.JoinLoose(sm, frame, JointType::kLock);
  try {
    d.JoinLoose(frame, sm, JointType::kHinge);
    FAIL() << "joined twice";
  } catch (const DesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("joined already"));
  }
}

TEST(StudioLooseJoin, AHingeClosingALoopIsRefusedByTheValidator) {
  Design d;
  for (int i = 0; i < 3; ++i) d.AddLoose(LoosePart::kFrame);
  const auto& f = d.scenario().loose_frames;
  const std::string a = f.at(0).guid, b = f.at(1).guid, c = f.at(2).guid;
  d.JoinLoose(a, b, JointType::kHinge);
  d.JoinLoose(b, c, JointType::kHinge);
  try {
    d.JoinLoose(c, a, JointType::kHinge);
    FAIL() << "a loop of hinges";
  } catch (const DesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("loop"));
  }
  EXPECT_EQ(d.scenario().loose_joints.size(), 2u);
}

TEST(StudioLooseJoin, ALoosePartMovedOnTheGroundTakesWhatIsJoinedAlong) {
  Design d = SnakeFrameAndSensorModule();
  d.AddLoose(LoosePart::kHinge);  // frames 1 and 2, not joined to the others
  const std::string frame = d.scenario().loose_frames.at(0).guid;
  const std::string sm = d.scenario().loose_sensor_modules.at(0).guid;
  d.JoinLoose(sm, frame, JointType::kLock);
  const Scenario before = d.scenario();

  // Dragging the sensor module moves the frame locked to it, not the hinge
  // pair nor the robot.
  const Selection picked{SelectionKind::kLooseSensorModule, 0, 0};
  EXPECT_EQ(
      LooseGroup(before, picked),
      (std::vector<Selection>{{SelectionKind::kLooseFrame, 0, 0},
                              {SelectionKind::kLooseSensorModule, 0, 0}}));
  d.MoveOnGround(picked, {{0.5, -0.2}, M_PI / 2});
  const Scenario& after = d.scenario();
  const Eigen::Vector3d shift = after.loose_sensor_modules[0].position -
                                before.loose_sensor_modules[0].position;
  EXPECT_GT(shift.head<2>().norm(), 0.3);
  EXPECT_NEAR(shift.z(), 0, 1e-12);
  // Rigidly: the two are as far apart as before, both turned a quarter.
  EXPECT_NEAR(
      (after.loose_frames[0].position - after.loose_sensor_modules[0].position)
          .norm(),
      (before.loose_frames[0].position -
       before.loose_sensor_modules[0].position)
          .norm(),
      1e-12);
  const Eigen::Vector3d x =
      after.loose_frames[0].quat_rotation * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x.y(), 1.0, 1e-9);
  EXPECT_EQ(after.loose_frames[1].position, before.loose_frames[1].position);
  EXPECT_EQ(after.loose_frames[2].position, before.loose_frames[2].position);
  EXPECT_EQ(after.robots, before.robots);

  // The hinge's joint selected drags its two frames.
  d.MoveOnGround({SelectionKind::kLooseJoint, 0, 0}, {{0.1, 0}, 0});
  EXPECT_NEAR(d.scenario().loose_frames[1].position.x(),
              before.loose_frames[1].position.x() + 0.1, 1e-12);
  EXPECT_NEAR(d.scenario().loose_frames[2].position.x(),
              before.loose_frames[2].position.x() + 0.1, 1e-12);
  d.Undo();
  d.Undo();
  EXPECT_EQ(d.scenario().loose_frames, before.loose_frames);
}

}  // namespace
}  // namespace mrsim::studio
