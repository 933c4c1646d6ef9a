// `mrsim-studio --select NAME`: the names a user types find the robot,
// object or part they mean, and a name that is not there says what is.
#include "studio/design/selection_name.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "sim_core/scenario/scenario_xml.h"
#include "studio/design/design.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using ::testing::HasSubstr;

Scenario CaseStudy() {
  return ReadScenarioFile(testing::SourcePath("scenarios/case_study.xml"));
}

TEST(SelectionName, FindsRobotsObjectsAndPartsByName) {
  const Scenario s = CaseStudy();
  EXPECT_EQ(SelectionNamed(s, "case_study"),
            (Selection{SelectionKind::kRobot, 0, 0}));
  EXPECT_EQ(SelectionNamed(s, "ball"),
            (Selection{SelectionKind::kSceneObject, 0, 0}));
  EXPECT_EQ(SelectionNamed(s, "module 2"),
            (Selection{SelectionKind::kModule, 0, 2}));
  EXPECT_EQ(SelectionNamed(s, "case_study sensor_module 1"),
            (Selection{SelectionKind::kSensorModule, 0, 1}));
  EXPECT_EQ(SelectionNamed(s, "terrain"),
            (Selection{SelectionKind::kScene, 0, 0}));
  EXPECT_EQ(SelectionNamed(s, "none"), Selection{});
}

TEST(SelectionName, AnUnknownNameSaysWhatThereIs) {
  const Scenario s = CaseStudy();
  for (const char* bad : {"crate", "module 99", "module", "module 1 2"}) {
    try {
      SelectionNamed(s, bad);
      ADD_FAILURE() << bad << " selected something";
    } catch (const DesignError& e) {
      EXPECT_THAT(e.what(), HasSubstr(std::string("'") + bad + "'"));
      EXPECT_THAT(e.what(), HasSubstr("robots: case_study; objects: ball"));
    }
  }
}

}  // namespace
}  // namespace mrsim::studio
