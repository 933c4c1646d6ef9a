// The studio's window contents, drawn with Dear ImGui each frame: the
// easy-mode palette and part list on the left, the inspector on the right,
// the 3-D preview between them, file dialogs, the template dialog, the
// unsaved-changes prompt and the help overlay. Every edit goes to the
// Design; this class holds no editing logic of its own. The platform
// shell (window or off-screen) owns the OpenGL context and ImGui's
// platform backend and calls Frame().
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "studio/design/design.h"
#include "studio/design/recent_files.h"
#include "studio/ui/file_browser.h"
#include "studio/ui/layout_recorder.h"
#include "studio/ui/live_panel.h"
#include "studio/ui/preview.h"

namespace mrsim::studio {

struct AppOptions {
  int width = 1280;  // largest frame the off-screen buffer must hold
  int height = 800;
  std::string layout_dump;   // --layout-dump file, "" for none
  std::string recent_store;  // RecentFiles store, "" for the default
};

class StudioApp {
 public:
  StudioApp(Design design, const AppOptions& options);
  ~StudioApp();

  // One frame: ImGui::NewFrame() .. render 3-D and ImGui into the bound
  // framebuffer of width x height pixels. The platform backend's NewFrame
  // (or DisplaySize/DeltaTime) must be set before.
  void Frame(int width, int height, bool offscreen);
  // The user closed the window: quits now, or asks first when unsaved.
  void RequestClose();
  // A key pressed in the window (GLFW key and modifier codes). Queued and
  // handled at the next frame, so a press shorter than a frame still counts.
  void OnKey(int key, int mods) { keys_.push_back({key, mods}); }
  bool should_quit() const { return quit_; }

  Design& design() { return design_; }
  LivePanel& live() { return *live_; }
  // The right column shows the Run panel (F5) instead of the Inspector.
  void ShowRunPanel(bool show) { show_run_ = show; }
  Preview& preview() { return *preview_; }
  // Why the preview could not be built from the design ("" when it was).
  const std::string& build_error() const { return build_error_; }
  // Time the last model rebuild took (ms), -1 before the first.
  double last_rebuild_ms() const { return last_rebuild_ms_; }

 private:
  enum class Pending { kNone, kNew, kOpen, kTemplate, kQuit };

  void DrawDesignPanel(float x, float y, float w, float h);
  void DrawInspector(float x, float y, float w, float h);
  void DrawStatus(float x, float y, float w);
  // Force plate on/off and distance sensors of the selected sensor module.
  void DrawSensorMounts(const Scenario& view, const Selection& sel);
  void DrawDialogs();
  void DrawHelp();
  void DrawTemplateDialog();
  void DrawBusyQuitDialog();
  void HandleViewInput(const mjrRect& view, float top_left_x, float top_left_y);
  void HandleKeys();
  bool Button(const char* label, float width = 0);
  void Record(const std::string& name);
  // Runs `action` now, or after the unsaved-changes prompt.
  void Guard(Pending action);
  void RunPending();
  void Try(const std::function<void()>& edit);
  // A button's action ("add the yaw module"): a refusal also opens a
  // dialog saying what was not done and why, so it cannot go unseen.
  void Try(const std::string& action, const std::function<void()>& edit);
  void DrawRefusalDialog();
  void OpenFile(const std::string& path);
  void SaveFile();
  void Note(const std::string& text);
  void Refuse(const std::string& text);
  // Where file dialogs open: beside the design, else ./scenarios when
  // there is one (the source tree), else the current folder.
  std::string StartFolder() const;

  Design design_;
  AppOptions options_;
  std::unique_ptr<Preview> preview_;
  LayoutRecorder layout_;
  std::unique_ptr<LivePanel> live_;
  bool show_run_ = false;  // the right column shows Run instead of Inspector
  RecentFiles recent_;
  FileBrowser browser_;
  enum class BrowseFor {
    kNone,
    kOpen,
    kSaveAs,
    kHeightImage
  } browse_for_ = BrowseFor::kNone;
  long built_revision_ = -1;
  int built_live_ = -1;  // live_scenario_revision() shown, -1: the design
  std::string build_error_;
  std::string message_;  // last note, refusal or error, in the status bar
  bool message_is_error_ = false;  // red, else a plain note ("saved ...")
  std::map<std::string, std::string> field_errors_;  // by field key
  std::map<std::string, std::string> field_edits_;   // text being typed
  long fields_revision_ = -1;  // the design the two maps above are for
  Selection fields_selection_;
  Where where_ = Where::kAfterSelection;
  Pending pending_ = Pending::kNone;
  std::string pending_path_;
  bool ask_unsaved_ = false;
  bool unsaved_shown_ = false;
  bool show_help_ = false;
  bool show_template_ = false;
  TemplateOptions template_;
  int template_pattern_ = 2;  // ChainPattern
  int template_sensors_ = 0;  // SensorPlacement
  int ray_face_ = 4;          // face for "add distance sensor": front
  // The design revision and selection ray_face_ was last defaulted for:
  // it moves to a face that would be accepted when they change.
  long ray_face_revision_ = -1;
  Selection ray_face_selection_;
  bool quit_ = false;
  // Quitting would stop what the Run panel has going: asked first.
  std::string ask_busy_quit_;  // the question, "" when not asking
  bool busy_quit_shown_ = false;
  std::string refused_action_;  // the action a dialog says was not done
  std::string refused_why_;
  bool refused_shown_ = false;
  bool view_drag_ = false;
  std::vector<std::pair<int, int>>
      keys_;  // key, mods  // a drag that started in the 3-D view
  double last_rebuild_ms_ = -1;
};

}  // namespace mrsim::studio
