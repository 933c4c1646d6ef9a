// What a drag does to the design, without a window: reordering and dropping
// parts in the chain, moving and turning robots and objects on the ground,
// several robots. Each drag is one undo step.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/chain_edit.h"
#include "studio/design/design.h"
#include "studio/design/ground_move.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using mrsim::testing::SourcePath;
using mrsim::testing::TempDir;

std::string Bytes(const Design& d) { return WriteScenarioString(d.scenario()); }

// pitch, sensor, yaw, sensor, pitch (front to back).
Design FiveParts() {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  d.AddPart(NextPart::kSensorModule);
  d.AddPart(NextPart::kYawModule);
  d.AddPart(NextPart::kSensorModule);
  d.AddPart(NextPart::kPitchModule);
  return d;
}

std::string Kinds(const Robot& robot) {
  std::string out;
  for (const ChainSlot& s : ChainOrder(robot)) {
    out += s.sensor ? 'S' : s.axis == Axis::kPitch ? 'P' : 'Y';
  }
  return out;
}

TEST(StudioDrag, ReorderingByDragIsOneUndoStep) {
  Design d = FiveParts();
  const std::string before = Bytes(d);
  d.MovePart(0, 4, 0);  // the tail's pitch module to the front
  EXPECT_EQ(Kinds(d.scenario().robots[0]), "PPSYS");
  EXPECT_EQ(d.selection(), (Selection{SelectionKind::kModule, 0, 0}));
  d.Undo();
  EXPECT_EQ(Bytes(d), before);
  d.Redo();
  EXPECT_EQ(Kinds(d.scenario().robots[0]), "PPSYS");
  // Dropped on its own place: nothing happens, no undo step.
  const std::string after = Bytes(d);
  d.MovePart(0, 2, 2);
  d.Undo();
  EXPECT_EQ(Kinds(d.scenario().robots[0]), "PSYSP");  // the drag undone
  EXPECT_NE(Bytes(d), after);
}

TEST(StudioDrag, AReorderThatPutsSensorModulesSideBySideIsRefused) {
  Design d = FiveParts();
  const std::string before = Bytes(d);
  EXPECT_THROW(d.MovePart(0, 2, 4), DesignError);  // S S at the tail
  EXPECT_THROW(d.MovePart(0, 0, 9), DesignError);  // no such place
  EXPECT_EQ(Bytes(d), before);
}

TEST(StudioDrag, AModuleDroppedFromThePaletteLandsBetweenTheParts) {
  Design d = FiveParts();
  d.InsertPart(NextPart::kYawModule, 0, 2);  // between S0 and the yaw module
  EXPECT_EQ(Kinds(d.scenario().robots[0]), "PSYYSP");
  EXPECT_EQ(d.selection(), (Selection{SelectionKind::kModule, 0, 1}));
  d.InsertPart(NextPart::kSensorModule, 0, 3);
  EXPECT_EQ(Kinds(d.scenario().robots[0]), "PSYSYSP");
  d.Undo();
  d.Undo();
  EXPECT_EQ(Bytes(d), Bytes(FiveParts()));
}

TEST(StudioDrag, DraggingARobotMovesAndTurnsEveryPartRigidly) {
  Design d = FiveParts();
  const Robot before = d.scenario().robots[0];
  const Eigen::Vector3d pivot = RobotPivot(before);
  d.MoveOnGround({SelectionKind::kRobot, 0, 0}, {{0.3, -0.1}, M_PI / 2});
  const Robot& after = d.scenario().robots[0];
  EXPECT_NEAR(RobotHeading(after), M_PI / 2, 1e-9);
  EXPECT_TRUE(
      RobotPivot(after).isApprox(pivot + Eigen::Vector3d(0.3, -0.1, 0), 1e-9));
  // Rigid: distances between parts are kept, heights too.
  const Eigen::Vector3d a0 = before.modules[0].position;
  const Eigen::Vector3d a2 = before.modules[2].position;
  const Eigen::Vector3d b0 = after.modules[0].position;
  const Eigen::Vector3d b2 = after.modules[2].position;
  EXPECT_NEAR((a2 - a0).norm(), (b2 - b0).norm(), 1e-9);
  EXPECT_NEAR(a0.z(), b0.z(), 1e-12);
  // The chain ran along +x; turned a quarter, it runs along +y.
  EXPECT_NEAR((b2 - b0).normalized().dot(Eigen::Vector3d::UnitY()),
              (a2 - a0).normalized().dot(Eigen::Vector3d::UnitX()), 1e-9);
  EXPECT_NO_THROW(Physics{d.scenario()});
  d.Undo();
  EXPECT_EQ(Bytes(d), WriteScenarioString([&] {
              Scenario s = d.scenario();
              s.robots[0] = before;
              return s;
            }()));
}

TEST(StudioDrag, ATurnedRobotKeepsItsHeadingWhenPartsAreAddedOrMoved) {
  Design d = FiveParts();
  d.MoveOnGround({SelectionKind::kModule, 0, 1}, {{1.0, 2.0}, 0.7});
  const Eigen::Vector3d hinge0 = d.scenario().robots[0].modules[0].position;
  d.InsertPart(NextPart::kPitchModule, 0, 5);
  d.MovePart(0, 0, 5);
  EXPECT_NEAR(RobotHeading(d.scenario().robots[0]), 0.7, 1e-9);
  EXPECT_TRUE(
      d.scenario().robots[0].modules[0].position.isApprox(hinge0, 1e-9));
}

TEST(StudioDrag, DraggingAnObjectMovesOnlyThatObjectAndSavesThere) {
  Design d = FiveParts();
  d.AddObject(ObjectKind::kBall);
  d.AddObject(ObjectKind::kBox);
  const Scenario before = d.scenario();
  d.MoveOnGround({SelectionKind::kSceneObject, 0, 0}, {{0.3, 0.0}, 0.0});
  d.MoveOnGround({SelectionKind::kSceneObject, 0, 1}, {{0.0, 0.0}, M_PI / 2});
  const std::string file = TempDir("studio_drag_object") + "/moved.xml";
  d.SaveAs(file);
  const Scenario saved = ReadScenarioFile(file);
  EXPECT_NEAR(saved.scene_objects[0].position.x(),
              before.scene_objects[0].position.x() + 0.3, 1e-9);
  EXPECT_TRUE(saved.scene_objects[1].position.isApprox(
      before.scene_objects[1].position, 1e-12));
  const Eigen::Vector3d x =
      saved.scene_objects[1].quat_rotation * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x.y(), 1.0, 1e-6);
  auto robots_only = [](const Scenario& from) {
    Scenario s;
    s.robots = from.robots;
    return WriteScenarioString(s);
  };
  EXPECT_EQ(robots_only(saved), robots_only(before));
  EXPECT_THROW(d.MoveOnGround({SelectionKind::kScene, 0, 0}, {{0.1, 0}, 0}),
               DesignError);
}

TEST(StudioDrag, SeveralRobotsStandSideBySideAndEachMovesAlone) {
  Design d = FiveParts();
  d.AddRobot();
  d.AddRobot();
  const Scenario& s = d.scenario();
  ASSERT_EQ(s.robots.size(), 3u);
  EXPECT_NE(s.robots[1].name, s.robots[0].name);
  EXPECT_NE(s.robots[2].name, s.robots[1].name);
  EXPECT_EQ(d.selection(), (Selection{SelectionKind::kRobot, 2, 0}));
  EXPECT_NO_THROW(Physics{s});
  // Parts go into the selected robot; moving it leaves the others.
  d.InsertPart(NextPart::kYawModule, 2, 1);
  EXPECT_EQ(Kinds(d.scenario().robots[2]), "PY");
  const std::string first = WriteScenarioString([&] {
    Scenario t;
    t.robots = {d.scenario().robots[0]};
    return t;
  }());
  d.MoveOnGround({SelectionKind::kRobot, 2, 0}, {{0.5, 0.5}, 1.0});
  EXPECT_EQ(WriteScenarioString([&] {
              Scenario t;
              t.robots = {d.scenario().robots[0]};
              return t;
            }()),
            first);
  EXPECT_NO_THROW(Physics{d.scenario()});
}

}  // namespace
}  // namespace mrsim::studio
