// The studio window's panel convention, after Dear ImGui's own examples
// (one function per window). Each panel or dialog is a class in its own
// file under studio/ui/, named after it (InspectorPanel in
// inspector_panel.h), holding only its own widget state (text being typed,
// a dialog's choices) and drawing itself once a frame:
//   void Draw(StudioContext& studio, const PanelRect& rect);  // a panel
//   void Draw(StudioContext& studio);                          // a dialog
// Everything panels share (the design, the preview, the status message,
// the action awaiting an answer) is in StudioContext; edits go to the
// Design through StudioContext::Try, so a refusal is shown the same way
// everywhere. StudioApp owns the context and the panels and calls them in
// drawing order. Buttons are RecordedButton (widgets.h), so the layout
// dump names them for the window tests.
#pragma once

namespace mrsim::studio {

// Where a docked panel goes: window pixels, top left.
struct PanelRect {
  float x = 0;
  float y = 0;
  float w = 0;
  float h = 0;
};

}  // namespace mrsim::studio
