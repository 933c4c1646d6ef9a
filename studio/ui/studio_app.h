// The studio's window contents, drawn with Dear ImGui each frame: the
// design panel on the left, the inspector or the Run panel on the right,
// the 3-D preview between them, the status bar, the dialogs and the help
// overlay, each its own class (panel.h). StudioApp owns them and what they
// share (StudioContext), lays them out, routes keys and mouse, and keeps
// the preview in step with the design. Every edit goes to the Design; this
// class holds no editing logic of its own. The platform shell (window or
// off-screen, studio/app/) owns the OpenGL context and ImGui's platform
// backend and calls Frame().
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "studio/ui/dialogs/busy_quit_dialog.h"
#include "studio/ui/panels/design_panel.h"
#include "studio/ui/dialogs/file_dialog.h"
#include "studio/ui/panels/ground_handles.h"
#include "studio/ui/dialogs/help_overlay.h"
#include "studio/ui/panels/inspector_panel.h"
#include "studio/ui/dialogs/refusal_dialog.h"
#include "studio/ui/panels/status_bar.h"
#include "studio/ui/studio_context.h"
#include "studio/ui/dialogs/template_dialog.h"
#include "studio/ui/dialogs/unsaved_dialog.h"

namespace mrsim::studio {

class StudioApp {
 public:
  StudioApp(Design design, const AppOptions& options);
  ~StudioApp();

  // One frame: ImGui::NewFrame() .. render 3-D and ImGui into the bound
  // framebuffer of width x height pixels. The platform backend's NewFrame
  // (or DisplaySize/DeltaTime) must be set before.
  void Frame(int width, int height, bool offscreen);
  // The user closed the window: quits now, or asks first when unsaved.
  void RequestClose() { studio_.RequestClose(); }
  // A key pressed in the window (GLFW key and modifier codes). Queued and
  // handled at the next frame, so a press shorter than a frame still counts.
  void OnKey(int key, int mods) { keys_.push_back({key, mods}); }
  bool should_quit() const { return studio_.quit; }
  // Frames should come at a steady rate: something live, or a video.
  bool animating() const {
    return studio_.live->animating() || studio_.video.recording();
  }
  // What --ui-scale asked for (0: the monitor's), and the scale in use.
  float requested_ui_scale() const { return studio_.options.ui_scale; }
  void SetUiScale(float scale) { studio_.panels.ui_scale = scale; }

  Design& design() { return studio_.design; }
  LivePanel& live() { return *studio_.live; }
  // The right column shows the Run panel (F5) instead of the Inspector.
  void ShowRunPanel(bool show) { studio_.show_run = show; }
  Preview& preview() { return *studio_.preview; }
  // The Run panel's camera picture (camera_feed.h).
  const CameraFeed& camera_feed() const { return *studio_.camera_feed; }
  // The 3-D view's OpenGL viewport in the last frame (benchmarks).
  const mjrRect& view() const { return view_; }
  // Why the preview could not be built from the design ("" when it was).
  const std::string& build_error() const { return studio_.build_error; }
  // Time the last model rebuild took (ms), -1 before the first.
  double last_rebuild_ms() const { return last_rebuild_ms_; }

 private:
  // Dragging a side panel's inner edge resizes it.
  void HandlePanelEdges(const PanelLayout& panels, int width);
  void HandleViewInput(const mjrRect& view, float top_left_x, float top_left_y);
  void HandleKeys();
  // The preview follows the design (or a live run's body): one rebuild per
  // change, then the states of a running simulation.
  void UpdatePreview();
  // The Run panel's camera picture from the preview's model and poses.
  void UpdateCameraFeed();
  // --layout-dump: selection, file, open dialog, message, part positions.
  void RecordState(const mjrRect& view, int height);

  StudioContext studio_;
  DesignPanel design_panel_;
  InspectorPanel inspector_;
  StatusBar status_;
  FileDialog file_dialog_;
  UnsavedDialog unsaved_;
  TemplateDialog template_;
  BusyQuitDialog busy_quit_;
  RefusalDialog refusal_;
  HelpOverlay help_;
  int built_live_ = -1;     // live_scenario_revision() shown, -1: the design
  GroundHandles handles_;   // move handle, heading ring, drops on the robot
  bool view_drag_ = false;  // a drag that started in the 3-D view
  mjrRect view_ = {0, 0, 16, 16};  // where the 3-D view was last drawn
  int resizing_ = 0;               // a panel edge dragged: 1 left, 2 right
  std::vector<std::pair<int, int>> keys_;  // key, mods
  double last_rebuild_ms_ = -1;
};

}  // namespace mrsim::studio
