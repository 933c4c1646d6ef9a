// Parts overlapping at the start are found with MuJoCo's own collision
// and named as the file names them; a robot lying on the ground with its
// parts face to face is fine.
#include "sim_core/export/overlap_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario_tool/scenario_command.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

TEST(OverlapCheck, ShippedScenariosHaveNoOverlaps) {
  for (const char* name : {"case_study.xml", "snake11.xml", "terrain.xml"}) {
    SCOPED_TRACE(name);
    const Scenario s =
        ReadScenarioFile(testing::SourcePath(std::string("scenarios/") + name));
    for (const PartOverlap& o : FindOverlaps(s)) {
      ADD_FAILURE() << DescribeOverlap(o);
    }
  }
}

TEST(OverlapCheck, SensorChainLyingOnTheGroundHasNoOverlaps) {
  ChainScenarioOptions options;
  options.chain.modules = 5;
  options.chain.sensor_after = SensorsAfter(SensorPlacement::kAll, 5);
  options.chain.force_sensors = true;
  options.chain.front_distance_sensor = true;
  EXPECT_THAT(FindOverlaps(MakeChainScenario(options)), IsEmpty());
}

Scenario RobotInsideABox() {
  Scenario s =
      ReadScenarioFile(testing::SourcePath("scenarios/case_study.xml"));
  SceneObject box;
  box.guid = "crate";
  box.is_static = true;
  box.size = Eigen::Vector3d(0.3, 0.3, 0.3);
  box.position = s.robots[0].modules[0].position;
  s.scene_objects.push_back(box);
  return s;
}

TEST(OverlapCheck, RobotPlacedInsideABoxIsReportedNamingBoth) {
  const Scenario s = RobotInsideABox();
  const std::vector<PartOverlap> overlaps = FindOverlaps(s);
  ASSERT_THAT(overlaps, ::testing::Not(IsEmpty()));
  // By the name the user gave it (its guid), not its index.
  const std::string object = "scene object 'crate'";
  bool named = false;
  for (const PartOverlap& o : overlaps) {
    named |= o.second == object && o.first.find("robot '") == 0 &&
             (o.first.find("module 0 front frame") != std::string::npos ||
              o.first.find("module 0 back frame") != std::string::npos);
    EXPECT_GT(o.depth, kOverlapTolerance);
  }
  EXPECT_TRUE(named) << DescribeOverlap(overlaps.front());
}

TEST(OverlapCheck, ChainInsideAHillOverlapsTheTerrain) {
  // The robot stands on the terrain's base (z = 0, what the reader's own
  // ground check allows) while the height field rises up to 1 m around it.
  ChainScenarioOptions options;
  options.chain.modules = 2;
  Scenario s = MakeChainScenario(options);
  s.base_dir = testing::SourcePath("scenarios");
  s.scene.height_image = "terrain.png";
  s.scene.height = 1.0;
  s.scene.meters_per_pixel = 0.02;
  s.scene.position = Eigen::Vector3d(-1, -1, 0);
  const std::vector<PartOverlap> overlaps = FindOverlaps(s);
  ASSERT_THAT(overlaps, ::testing::Not(IsEmpty()));
  for (const PartOverlap& o : overlaps) {
    EXPECT_EQ(o.second, "the terrain");
    EXPECT_EQ(o.second_path, "Scenario/scene");
    EXPECT_THAT(o.first, HasSubstr("robot 'snake' module"));
  }
  // Flat ground under the same robot: nothing.
  s.scene.height_image.clear();
  EXPECT_THAT(FindOverlaps(s), IsEmpty());
}

TEST(OverlapCheck, ObjectsWithAGeneratedGuidAreNamedByTheirIndex) {
  Scenario s = RobotInsideABox();
  s.scene_objects.back().guid = "7b579252-58ce-4fb0-937f-57c24696363f";
  const std::string object =
      "scene object " + std::to_string(s.scene_objects.size() - 1);
  const std::vector<PartOverlap> overlaps = FindOverlaps(s);
  ASSERT_THAT(overlaps, ::testing::Not(IsEmpty()));
  EXPECT_EQ(overlaps.front().second, object);
}

TEST(OverlapCheck, RefuseOverlapsNamesEveryPairWithFileAndLine) {
  const std::string dir = testing::TempDir("overlap_refuse");
  const std::string file = dir + "/boxed.xml";
  WriteScenarioFile(RobotInsideABox(), file);
  ScenarioSource source;
  ScenarioReadOptions read;
  read.source_out = &source;
  const Scenario s = ReadScenarioFile(file, read);
  try {
    RefuseOverlaps(s, &source);
    FAIL() << "a robot inside a box was not refused";
  } catch (const OverlapError& e) {
    EXPECT_EQ(e.overlaps().size(), FindOverlaps(s).size());
    for (const PartOverlap& o : e.overlaps()) {
      EXPECT_THAT(e.what(), HasSubstr(DescribeOverlap(o, &source)));
    }
    EXPECT_THAT(e.what(), HasSubstr("scene object 'crate' by "));
  }
  EXPECT_NO_THROW(RefuseOverlaps(
      ReadScenarioFile(testing::SourcePath("scenarios/lua_serpenoid.xml"))));
}

TEST(OverlapCheck, TwoRobotsInTheSamePlaceOverlapEachOther) {
  ChainScenarioOptions options;
  options.chain.modules = 2;
  Scenario s = MakeChainScenario(options);
  Robot second = s.robots[0];
  second.name = "twin";
  for (Module& m : second.modules) {
    for (Frame& f : m.frames) f.guid += "_twin";
    m.joint.left_frame_guid += "_twin";
    m.joint.right_frame_guid += "_twin";
    m.joint.guid += "_twin";
  }
  for (Joint& j : second.locks) {
    j.guid += "_twin";
    j.left_frame_guid += "_twin";
    j.right_frame_guid += "_twin";
  }
  s.robots.push_back(second);
  const std::vector<PartOverlap> overlaps = FindOverlaps(s);
  ASSERT_THAT(overlaps, ::testing::Not(IsEmpty()));
  EXPECT_THAT(overlaps.front().first, HasSubstr("robot 'snake'"));
  EXPECT_THAT(overlaps.front().second, HasSubstr("robot 'twin'"));
}

TEST(OverlapCheck, ValidateCommandFailsWithFileLineAndBothParts) {
  const std::string dir = testing::TempDir("overlap_validate");
  const std::string file = dir + "/boxed.xml";
  WriteScenarioFile(RobotInsideABox(), file);
  ScenarioCommand command;
  command.action = ScenarioAction::kValidate;
  command.file = file;
  std::ostringstream out, info;
  try {
    RunScenarioCommand(command, out, info);
    FAIL() << "validate accepted a robot inside a box";
  } catch (const ScenarioInputError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr(file + ":"));
    EXPECT_THAT(what, HasSubstr("Scenario/robot[1]/modules/Module[1]/frames/"
                                "Frame[1]: robot '"));
    EXPECT_THAT(what, HasSubstr("module 0 front frame overlaps scene object"));
    // A line number, not 0.
    EXPECT_THAT(what, ::testing::Not(HasSubstr(file + ":0:")));
  }
}

TEST(OverlapCheck, ValidateCommandAcceptsTheCaseStudy) {
  ScenarioCommand command;
  command.action = ScenarioAction::kValidate;
  command.file = testing::SourcePath("scenarios/case_study.xml");
  std::ostringstream out, info;
  RunScenarioCommand(command, out, info);
  EXPECT_THAT(out.str(), HasSubstr(": ok ("));
}

}  // namespace
}  // namespace mrsim
