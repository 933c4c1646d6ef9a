// Where the studio window's panels go: the design panel on the left, the
// inspector or Run panel on the right, the status bar over the 3-D view
// between them. Each side panel can be hidden (Tab, Shift+Tab, as in
// MuJoCo's simulate) or widened by dragging its inner edge; text and
// widths grow with the UI scale (high-DPI screens). Plain arithmetic, so
// a test can check that no two panels overlap at any window size.
#pragma once

namespace mrsim::studio {

// A rectangle in window pixels, top left; w == 0 when hidden.
struct LayoutRect {
  float x = 0;
  float y = 0;
  float w = 0;
  float h = 0;
  float right() const { return x + w; }
};

// What the user chose: which panels show and how wide (pixels at UI scale
// 1, so a width survives a scale change).
struct PanelSettings {
  bool show_left = true;
  bool show_right = true;
  float left_width = 330;
  float right_width = 400;
  float ui_scale = 1;  // text and widget size, 1 = 15 px text
};

// The narrowest a shown side panel gets (at scale 1), and the share of the
// window the 3-D view keeps when both panels would not fit.
inline constexpr float kMinPanelWidth = 200;
inline constexpr float kMinViewShare = 0.3f;
inline constexpr float kStatusHeight = 30;

struct PanelLayout {
  LayoutRect left;    // w == 0: hidden
  LayoutRect right;   // w == 0: hidden
  LayoutRect view;    // the 3-D view, under the status bar
  LayoutRect status;  // over the top of the view
};

// Lays out a window of width x height pixels. Shown panels keep their
// chosen widths while the 3-D view keeps kMinViewShare of the width;
// otherwise both shrink in proportion, down to kMinPanelWidth (scaled),
// and then the view gets what is left (at least 16 px). Panels never
// overlap each other or the view and never leave the window.
PanelLayout LayOutPanels(int width, int height, const PanelSettings& settings);

// The UI scale for a monitor content scale (GLFW's, 1 on a plain screen,
// 2 on most high-DPI ones) or a --ui-scale value: 0 or less means "from
// the monitor"; the result is clamped to [0.5, 4].
float ChooseUiScale(float requested, float monitor_scale);

}  // namespace mrsim::studio
