// The studio window's panel layout: no overlaps at any size, hidden panels
// give the 3-D view their room, the UI scale widens panels.
#include "studio/design/panel_layout.h"

#include <gtest/gtest.h>

namespace mrsim::studio {
namespace {

// Left panel, view and right panel side by side inside the window.
void ExpectSideBySide(const PanelLayout& l, int width, int height) {
  EXPECT_GE(l.left.x, 0);
  EXPECT_LE(l.left.right(), l.view.x + 0.01f);
  EXPECT_LE(l.view.right(), l.right.x + 0.01f);
  EXPECT_LE(l.right.right(), width + 0.01f);
  EXPECT_GE(l.view.w, 16);
  EXPECT_FLOAT_EQ(l.status.x, l.view.x);
  EXPECT_FLOAT_EQ(l.status.w, l.view.w);
  EXPECT_FLOAT_EQ(l.view.y, l.status.h);
  EXPECT_FLOAT_EQ(l.view.y + l.view.h, static_cast<float>(height));
}

TEST(PanelLayout, NoPanelsOverlapFromTinyToLargeWindows) {
  for (float scale : {1.0f, 1.5f, 2.0f}) {
    for (int width : {200, 480, 640, 729, 800, 1024, 1280, 1920, 3840}) {
      PanelSettings s;
      s.ui_scale = scale;
      SCOPED_TRACE(std::to_string(width) + " px at scale " +
                   std::to_string(scale));
      ExpectSideBySide(LayOutPanels(width, 640, s), width, 640);
    }
  }
}

TEST(PanelLayout, At1024By640BothPanelsAndAUsableViewFit) {
  const PanelLayout l = LayOutPanels(1024, 640, PanelSettings());
  EXPECT_GE(l.left.w, kMinPanelWidth);
  EXPECT_GE(l.right.w, kMinPanelWidth);
  EXPECT_GE(l.view.w, 1024 * kMinViewShare - 0.5f);
  ExpectSideBySide(l, 1024, 640);
}

TEST(PanelLayout, ChosenWidthsKeptWhenThereIsRoom) {
  PanelSettings s;
  s.left_width = 300;
  s.right_width = 450;
  const PanelLayout l = LayOutPanels(1600, 900, s);
  EXPECT_FLOAT_EQ(l.left.w, 300);
  EXPECT_FLOAT_EQ(l.right.w, 450);
  EXPECT_FLOAT_EQ(l.right.x, 1150);
}

TEST(PanelLayout, HiddenPanelsGiveTheViewTheirRoom) {
  PanelSettings s;
  s.show_left = false;
  PanelLayout l = LayOutPanels(1280, 800, s);
  EXPECT_FLOAT_EQ(l.left.w, 0);
  EXPECT_FLOAT_EQ(l.view.x, 0);
  EXPECT_FLOAT_EQ(l.view.w, 1280 - 400);
  s.show_right = false;
  l = LayOutPanels(1280, 800, s);
  EXPECT_FLOAT_EQ(l.right.w, 0);
  EXPECT_FLOAT_EQ(l.view.w, 1280);  // the full-window 3-D view
  EXPECT_FLOAT_EQ(l.view.h, 800 - kStatusHeight);
}

TEST(PanelLayout, UiScaleWidensPanelsAndTheStatusBar) {
  PanelSettings s;
  s.ui_scale = 2;
  const PanelLayout l = LayOutPanels(3840, 2160, s);
  EXPECT_FLOAT_EQ(l.left.w, 660);
  EXPECT_FLOAT_EQ(l.right.w, 800);
  EXPECT_FLOAT_EQ(l.status.h, 2 * kStatusHeight);
}

TEST(PanelLayout, UiScaleFromTheFlagElseTheMonitor) {
  EXPECT_FLOAT_EQ(ChooseUiScale(0, 2), 2);
  EXPECT_FLOAT_EQ(ChooseUiScale(1.25f, 2), 1.25f);
  EXPECT_FLOAT_EQ(ChooseUiScale(0, 0), 1);
  EXPECT_FLOAT_EQ(ChooseUiScale(10, 1), 4);
  EXPECT_FLOAT_EQ(ChooseUiScale(0.1f, 1), 0.5f);
}

}  // namespace
}  // namespace mrsim::studio
