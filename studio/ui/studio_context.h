// What the panels and dialogs of the studio window share (panel.h): the
// Design being edited, the 3-D preview, the Run panel, the layout dump, the
// status message, the file dialog and the action waiting for an answer,
// with the actions several panels offer (save, open, guard against losing
// unsaved changes, try an edit). StudioApp owns one.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim_core/export/overlap_check.h"
#include "studio/design/design.h"
#include "studio/design/panel_layout.h"
#include "studio/design/recent_files.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/view/camera_feed.h"
#include "studio/ui/view/preview.h"
#include "studio/ui/view/view_recorder.h"
#include "studio/ui/widgets/file_browser.h"
#include "studio/ui/widgets/layout_recorder.h"

namespace mrsim::studio {

struct AppOptions {
  int width = 1280;  // largest frame the off-screen buffer must hold
  int height = 800;
  std::string layout_dump;   // --layout-dump file, "" for none
  std::string recent_store;  // RecentFiles store, "" for the default
  float ui_scale = 0;  // --ui-scale: text and panel size, 0: the monitor's
  // --full-view: both side panels hidden at the start (F11).
  bool full_view = false;
  // "New robot from template" is up at the start: mrsim-studio opened with
  // no file (from the desktop menu) offers a robot instead of an empty
  // world.
  bool open_template = false;
};

// An action that may first ask about unsaved changes.
enum class Pending { kNone, kNew, kOpen, kTemplate, kQuit };
// What the open file dialog is choosing a file for.
enum class BrowseFor {
  kNone,
  kOpen,
  kSaveAs,
  kHeightImage,
  kExportStl,  // a folder for the STL files (print_section.h)
  kFrameMesh,  // an OBJ/STL for the selected module's frames
  kKindMesh,   // an OBJ/STL for every module of the selected one's kind
};

struct StudioContext {
  StudioContext(Design design, const AppOptions& options);
  ~StudioContext();

  Design design;
  AppOptions options;
  std::unique_ptr<Preview> preview;
  // The Run panel's camera picture, rendered with the preview's model and
  // poses (after it: destroyed first, while the context is current).
  std::unique_ptr<CameraFeed> camera_feed;
  LayoutRecorder layout;
  std::unique_ptr<LivePanel> live;
  RecentFiles recent;
  FileBrowser browser;
  BrowseFor browse_for = BrowseFor::kNone;
  bool show_run = false;  // the right column shows Run instead of Inspector
  PanelSettings panels;   // which side panels show, their widths, UI scale
  ViewRecorder video;     // the 3-D view to an MP4
  bool show_help = false;
  // Save and Save As write the terrain and meshes into the file (base64).
  // A design is one self-contained file unless the user unticks it; an
  // opened file shows it as it was saved (NamesAssetFiles).
  bool embed_on_save = true;
  bool show_template = false;
  bool quit = false;
  long built_revision = -1;           // the design revision the preview shows
  std::string build_error;            // why the preview could not be built
  std::vector<PartOverlap> overlaps;  // in the design shown, at the start
  // Meshes that look drawn in millimetres (Design::OversizedMeshes), for
  // the design shown; measured once per rebuild.
  std::vector<Design::OversizedMesh> oversized_meshes;
  std::string message;  // last note, refusal or error, in the status bar
  bool message_is_error = false;  // red, else a plain note ("saved ...")
  Pending pending = Pending::kNone;
  std::string pending_path;  // a recent file to open once asked
  bool ask_unsaved = false;  // the unsaved-changes prompt is up
  // Quitting would stop what the Run panel has going: asked first.
  std::string ask_busy_quit;   // the question, "" when not asking
  std::string refused_action;  // the action a dialog says was not done
  std::string refused_why;

  // A recorded button (widgets.h) and the last item recorded by name.
  bool Button(const char* label, float width = 0);
  void Record(const std::string& name);
  void Try(const std::function<void()>& edit);
  // A button's action ("add the yaw module"): a refusal also opens a
  // dialog saying what was not done and why, so it cannot go unseen.
  void Try(const std::string& action, const std::function<void()>& edit);
  void Note(const std::string& text);
  void Refuse(const std::string& text);
  // Runs `action` now, or after the unsaved-changes prompt.
  void Guard(Pending action);
  void RunPending();
  // The user closed the window: quits now, or asks first when unsaved or
  // when something runs.
  void RequestClose();
  void OpenFile(const std::string& path);
  void SaveFile();
  // The Run panel's form and the Optimise section's into the design, so
  // Save writes how to run and optimise it.
  // Throws DesignError for a form no run could use.
  void StoreRunSettings();
  // Starts a video of the 3-D view beside the design (else in the
  // current folder), or stops it and says where it went and its size.
  void ToggleVideo();
  // Tab, Shift+Tab and F11: one side panel, or both for the full-window
  // 3-D view (both come back when both were hidden).
  void ToggleFullView();
  // Opens the file dialog for Save As.
  void BrowseSaveAs();
  // Where file dialogs open: beside the design, else ./scenarios when
  // there is one (the source tree), else the current folder.
  std::string StartFolder() const;
  // Where Open starts: StartFolder(), but the installed examples
  // (/usr/share/mrsim/scenarios) rather than a current folder without
  // scenarios, such as the home folder the desktop menu starts in.
  std::string OpenFolder() const;
};

}  // namespace mrsim::studio
