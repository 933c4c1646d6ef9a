// The Run panel's controller choice keeps what an opened design says.
#include "studio/ui/run/controller_panel.h"

#include <gtest/gtest.h>

namespace mrsim::studio {
namespace {

TEST(StudioControllerPanel, AGaitThatIsNoPresetSurvivesOpeningAndSaving) {
  ControllerPanel panel;
  EXPECT_EQ(panel.gait(), "forward");
  panel.Set(ControllerKind::kGait, "my-sidewind", "", "");
  EXPECT_EQ(panel.gait(), "my-sidewind");
  panel.Set(ControllerKind::kGait, "turn-wide", "", "");
  EXPECT_EQ(panel.gait(), "turn-wide");
  panel.Set(ControllerKind::kLua, "forward", "", "");
  EXPECT_EQ(panel.gait(), "forward");
  EXPECT_EQ(panel.kind(), ControllerKind::kLua);
}

}  // namespace
}  // namespace mrsim::studio
