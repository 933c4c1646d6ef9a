// Locks and loose parts in the studio's editing model, without a window:
// a robot's locks selected and edited (breaking force), loop locks
// attached and detached, loose frames, hinges and sensor modules added,
// edited and removed, and the fields that do nothing where they sit
// (REQ-1.3.4, REQ-1.4.5).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/chain_edit.h"
#include "studio/design/design.h"
#include "studio/design/inert_fields.h"
#include "studio/design/inspector_fields.h"

namespace mrsim::studio {
namespace {

using ::testing::HasSubstr;

Design ThreeModuleSnake() {
  Design d;
  d.AddPart(NextPart::kPitchModule);
  d.AddPart(NextPart::kYawModule);
  d.AddPart(NextPart::kPitchModule);
  return d;
}

std::set<std::string> Offered(Scenario s, const Selection& sel) {
  std::set<std::string> names;
  for (const FieldGroup& g : InspectorFields(s, sel)) {
    for (const FieldRef& f : g.fields) names.insert(f.info().xml);
  }
  return names;
}

TEST(StudioLocks, ALockIsSelectedAndItsBreakingForceEditedAndKept) {
  Design d = ThreeModuleSnake();
  ASSERT_EQ(d.scenario().robots[0].locks.size(), 2u);
  const Selection lock{SelectionKind::kLock, 0, 1};
  d.Select(lock);
  ASSERT_EQ(d.selection(), lock);
  // A lock is rigid: its breaking force, and the parts it joins to read.
  const std::set<std::string> offered = Offered(d.scenario(), lock);
  EXPECT_EQ(offered.count("breakForce"), 1u);
  EXPECT_EQ(offered.count("leftFrameGuid"), 1u);
  for (const char* servo : {"type", "Kp", "max_vel", "velocityGain",
                            "maxTorque", "lowerRangeLimit", "servo"}) {
    EXPECT_EQ(offered.count(servo), 0u) << servo << " offered on a lock";
  }
  d.SetField({lock, "", "breakForce"}, "40");
  EXPECT_EQ(d.scenario().robots[0].locks[1].break_force, 40);
  // Laid out again (a module added at the tail), the same lock keeps it.
  d.AddPart(NextPart::kPitchModule, Where::kTail);
  int forty = 0;
  for (const Joint& j : d.scenario().robots[0].locks) {
    if (j.break_force == 40) ++forty;
  }
  EXPECT_EQ(forty, 1);
  // Round trip through the file.
  const Scenario back =
      ReadScenarioString(WriteScenarioString(d.scenario()), "design", "");
  EXPECT_EQ(back, d.scenario());
}

TEST(StudioLocks, ALoopLockIsAttachedCarriedThroughEditsAndDetached) {
  Design d = ThreeModuleSnake();
  const Robot& r = d.scenario().robots[0];
  const std::string head = r.modules[0].frames[0].guid;
  const std::string tail = r.modules[2].frames[1].guid;
  // The head may be locked to the tail; not to its own back frame (the
  // hinge joins them) nor to itself.
  std::vector<LockEnd> to = d.AttachableTo(0, head);
  bool tail_offered = false;
  for (const LockEnd& e : to) {
    EXPECT_NE(e.guid, head);
    EXPECT_NE(e.guid, r.modules[0].frames[1].guid);
    tail_offered |= e.guid == tail;
  }
  EXPECT_TRUE(tail_offered);
  EXPECT_THROW(d.AttachLock(0, head, r.modules[0].frames[1].guid), DesignError);
  d.AttachLock(0, head, tail);
  ASSERT_EQ(d.selection().kind, SelectionKind::kLock);
  const int loop = d.selection().index;
  EXPECT_FALSE(
      IsChainLock(d.scenario().robots[0], d.scenario().robots[0].locks[loop]));
  EXPECT_NO_THROW(ValidateScenario(d.scenario()));
  // Attaching the same pair twice is refused, naming the parts.
  try {
    d.AttachLock(0, tail, head);
    FAIL() << "attached twice";
  } catch (const DesignError& e) {
    EXPECT_THAT(e.what(), HasSubstr("joined already"));
  }
  // A part added in front renames the frames: the loop lock follows them.
  d.AddPart(NextPart::kPitchModule, Where::kFront);
  const Robot& grown = d.scenario().robots[0];
  int loops = 0;
  for (const Joint& j : grown.locks) {
    if (IsChainLock(grown, j)) continue;
    ++loops;
    EXPECT_EQ(j.left_frame_guid, grown.modules[1].frames[0].guid);
    EXPECT_EQ(j.right_frame_guid, grown.modules[3].frames[1].guid);
  }
  EXPECT_EQ(loops, 1);
  // A chain's own lock holds it together: detaching it is refused.
  for (int k = 0; k < static_cast<int>(grown.locks.size()); ++k) {
    if (!IsChainLock(grown, grown.locks[k])) continue;
    d.Select({SelectionKind::kLock, 0, k});
    try {
      d.DetachLock();
      FAIL() << "a chain lock detached";
    } catch (const DesignError& e) {
      EXPECT_THAT(e.what(), HasSubstr("holds the chain together"));
    }
    break;
  }
  // The loop lock detaches (Remove does the same).
  for (int k = 0; k < static_cast<int>(grown.locks.size()); ++k) {
    if (IsChainLock(grown, grown.locks[k])) continue;
    d.Select({SelectionKind::kLock, 0, k});
    d.RemoveSelected();
    break;
  }
  for (const Joint& j : d.scenario().robots[0].locks) {
    EXPECT_TRUE(IsChainLock(d.scenario().robots[0], j)) << j.guid;
  }
  d.Undo();
  EXPECT_EQ(d.scenario().robots[0].locks.size(), 4u);  // 3 chain + loop
}

// A lock from a module's front frame to the next module's front frame
// braces the hinge between them: a loop lock, though the two modules are
// neighbours, and it detaches.
TEST(StudioLocks, ALockAcrossAHingeIsALoopLockAndDetaches) {
  Design d = ThreeModuleSnake();
  const Robot& r = d.scenario().robots[0];
  d.AttachLock(0, r.modules[0].frames[0].guid, r.modules[1].frames[0].guid);
  const Robot& now = d.scenario().robots[0];
  EXPECT_FALSE(IsChainLock(now, now.locks.at(d.selection().index)));
  EXPECT_TRUE(IsChainLock(now, now.locks.at(0)));
  d.DetachLock();
  EXPECT_EQ(d.scenario().robots[0].locks.size(), 2u);
}

TEST(StudioLoose, LoosePartsAreAddedBesideTheRobotEditedAndRemoved) {
  Design d = ThreeModuleSnake();
  d.AddLoose(LoosePart::kFrame);
  ASSERT_EQ(d.scenario().loose_frames.size(), 1u);
  EXPECT_EQ(d.selection(), (Selection{SelectionKind::kLooseFrame, 0, 0}));
  // Beside the robot, resting on its ground.
  const Frame& f = d.scenario().loose_frames[0];
  EXPECT_LT(f.position.y(), d.scenario().robots[0].modules[0].position.y());
  EXPECT_NEAR(f.position.z() - f.scale.z() / 2,
              OptionsOf(d.scenario().robots[0]).origin.z(), 1e-12);
  d.SetField({d.selection(), "", "mass"}, "0.3");
  EXPECT_EQ(d.scenario().loose_frames[0].mass, 0.3);

  d.AddLoose(LoosePart::kSensorModule);
  ASSERT_EQ(d.scenario().loose_sensor_modules.size(), 1u);
  EXPECT_EQ(d.selection(),
            (Selection{SelectionKind::kLooseSensorModule, 0, 0}));
  const std::set<std::string> sm = Offered(d.scenario(), d.selection());
  EXPECT_EQ(sm.count("mass"), 1u);
  EXPECT_EQ(sm.count("leftMod_Nr"), 0u);  // no chain to sit in

  // A hinge: two frames and the joint between them, selected.
  d.AddLoose(LoosePart::kHinge);
  ASSERT_EQ(d.scenario().loose_joints.size(), 1u);
  ASSERT_EQ(d.scenario().loose_frames.size(), 3u);
  const Selection joint{SelectionKind::kLooseJoint, 0, 0};
  EXPECT_EQ(d.selection(), joint);
  std::set<std::string> hinge = Offered(d.scenario(), joint);
  EXPECT_EQ(hinge.count("type"), 1u);
  EXPECT_EQ(hinge.count("lowerRangeLimit"), 1u);
  EXPECT_EQ(hinge.count("breakForce"), 0u);
  // Passive until its servo is switched on; then the servo's gains show.
  EXPECT_EQ(hinge.count("servo"), 1u);
  EXPECT_EQ(hinge.count("Kp"), 0u);
  d.SetField({joint, "", "servo"}, "true");
  hinge = Offered(d.scenario(), joint);
  for (const char* gain : {"Kp", "max_vel", "velocityGain", "maxTorque"}) {
    EXPECT_EQ(hinge.count(gain), 1u) << gain;
  }
  d.SetField({joint, "", "Kp"}, "6");
  EXPECT_TRUE(d.scenario().loose_joints[0].servo);
  EXPECT_EQ(d.scenario().loose_joints[0].kp, 6);
  // Made a Lock, it keeps no servo (a lock never turns).
  d.SetField({joint, "", "type"}, "Lock");
  EXPECT_FALSE(d.scenario().loose_joints[0].servo);
  std::set<std::string> lock = Offered(d.scenario(), joint);
  EXPECT_EQ(lock.count("breakForce"), 1u);
  EXPECT_EQ(lock.count("lowerRangeLimit"), 0u);
  EXPECT_EQ(lock.count("servo"), 0u);
  d.SetField({joint, "", "breakForce"}, "12");
  EXPECT_EQ(d.scenario().loose_joints[0].break_force, 12);
  EXPECT_NO_THROW(ValidateScenario(d.scenario()));
  const Scenario back =
      ReadScenarioString(WriteScenarioString(d.scenario()), "design", "");
  EXPECT_EQ(back, d.scenario());

  // Removing one of the hinge's frames takes its joint along.
  d.Select({SelectionKind::kLooseFrame, 0, 1});
  d.RemoveSelected();
  EXPECT_EQ(d.scenario().loose_frames.size(), 2u);
  EXPECT_TRUE(d.scenario().loose_joints.empty());
  d.Select({SelectionKind::kLooseSensorModule, 0, 0});
  d.RemoveSelected();
  EXPECT_TRUE(d.scenario().loose_sensor_modules.empty());
}

TEST(StudioLoose, AnEmptyDesignTakesLooseParts) {
  Design d;
  d.AddLoose(LoosePart::kHinge);
  EXPECT_EQ(d.scenario().loose_frames.size(), 2u);
  d.AddLoose(LoosePart::kSensorModule);
  EXPECT_NO_THROW(ValidateScenario(d.scenario()));
}

// REQ-1.4.5: a flat ground has no pixels; a sphere has one size.
TEST(StudioInspector, AFlatGroundOffersNoPixelFields) {
  Scenario s = MakeChainScenario(ChainScenarioOptions{});
  s.scene.height_image.clear();
  const Selection terrain{SelectionKind::kScene, 0, 0};
  std::set<std::string> flat = Offered(s, terrain);
  EXPECT_EQ(flat.count("metersPerPixel"), 0u);
  EXPECT_EQ(flat.count("height"), 0u);
  EXPECT_EQ(flat.count("materialName"), 1u);
  s.scene.height_image = "hills.png";
  std::set<std::string> image = Offered(s, terrain);
  EXPECT_EQ(image.count("metersPerPixel"), 1u);
  EXPECT_EQ(image.count("height"), 1u);
}

TEST(StudioInspector, ASphereOffersItsDiameterAlone) {
  ASSERT_EQ(SizeComponents(PrimitiveShape::kSphere).size(), 1u);
  EXPECT_STREQ(SizeComponents(PrimitiveShape::kSphere)[0].label, "diameter");
  EXPECT_EQ(SizeComponents(PrimitiveShape::kCapsule).size(), 2u);
  EXPECT_EQ(SizeComponents(PrimitiveShape::kCapsule)[1].axis, 2);
  EXPECT_EQ(SizeComponents(PrimitiveShape::kBox).size(), 3u);
  EXPECT_EQ(SizeFor(PrimitiveShape::kSphere, Eigen::Vector3d(0.2, 1, 3)),
            Eigen::Vector3d(0.2, 0.2, 0.2));
  EXPECT_EQ(SizeFor(PrimitiveShape::kCylinder, Eigen::Vector3d(0.2, 1, 3)),
            Eigen::Vector3d(0.2, 0.2, 3));
}

}  // namespace
}  // namespace mrsim::studio
