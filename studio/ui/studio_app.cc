#include "studio/ui/studio_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "sim_core/codec/state_message.h"
#include "studio/ui/dialogs/print_section.h"
#include "studio/ui/widgets/gui_setup.h"
#include "studio/ui/widgets/panel_background.h"

namespace mrsim::studio {
namespace {

PanelRect ToPanelRect(const LayoutRect& r) { return {r.x, r.y, r.w, r.h}; }

std::string RectText(const LayoutRect& r) {
  if (r.w <= 0) return "hidden";
  char text[64];
  std::snprintf(text, sizeof(text), "%.0f %.0f %.0f %.0f", r.x, r.y, r.w, r.h);
  return text;
}

}  // namespace

StudioApp::StudioApp(Design design, const AppOptions& options)
    : studio_(std::move(design), options) {
  // Before any OpenGL context: every shell makes its context after this.
  PreferOneSoftwareRenderThread();
}

StudioApp::~StudioApp() = default;

void StudioApp::Frame(int width, int height, bool offscreen) {
  ImGui::NewFrame();
  studio_.layout.BeginFrame();
  HandleKeys();

  LivePanel& live = *studio_.live;
  live.Poll();
  const PanelLayout panels = LayOutPanels(width, height, studio_.panels);
  HandlePanelEdges(panels, width);
  if (panels.left.w > 0) {
    design_panel_.Draw(studio_, ToPanelRect(panels.left));
  }
  if (panels.right.w > 0 && studio_.show_run) {
    LiveDesign run;
    run.path = studio_.design.path();
    run.dirty = studio_.design.dirty();
    for (const Robot& r : studio_.design.scenario().robots) {
      run.robots.push_back(r.name);
    }
    for (const PartOverlap& o : studio_.overlaps) {
      char depth[32];
      std::snprintf(depth, sizeof depth, ": %.1f mm", o.depth * 1000);
      run.overlaps.push_back(o.first + " / " + o.second + depth);
    }
    run.save = [this] {
      studio_.SaveFile();
      return studio_.design.dirty() ? std::string() : studio_.design.path();
    };
    run.camera = studio_.camera_feed.get();
    live.Draw(panels.right.x, 0, panels.right.w, panels.right.h, run);
  } else if (panels.right.w > 0) {
    inspector_.Draw(studio_, ToPanelRect(panels.right));
  }
  status_.Draw(studio_, ToPanelRect(panels.status));
  live.DrawOverlay(panels.view.x + 8, panels.view.y + 8);
  // The dialogs, in the order they stack.
  file_dialog_.Draw(studio_);
  unsaved_.Draw(studio_);
  if (studio_.show_template) template_.Draw(studio_);
  busy_quit_.Draw(studio_);
  refusal_.Draw(studio_);
  if (studio_.show_help) help_.Draw(studio_);

  // OpenGL's rectangle: bottom-left origin; the view reaches the bottom.
  const mjrRect view = {static_cast<int>(panels.view.x), 0,
                        std::max(16, static_cast<int>(panels.view.w)),
                        std::max(16, static_cast<int>(panels.view.h))};
  view_ = view;
  HandleViewInput(view, panels.view.x, panels.view.y);
  UpdatePreview();
  if (panels.right.w > 0 && studio_.show_run) UpdateCameraFeed();

  ImGui::Render();
  // Clear the whole frame, then the 3-D view, then the panels over it.
  Preview& preview = *studio_.preview;
  preview.Bind(offscreen);
  glViewport(0, 0, width, height);
  // The panels' background colour: they draw none (panel_background.h).
  const ImVec4 clear = PanelClearColour();
  glClearColor(clear.x, clear.y, clear.z, 1.0f);
  glDisable(GL_SCISSOR_TEST);
  // Stencil too: a depth-stencil buffer cleared whole is a fast clear,
  // depth alone a read-modify-write of every pixel on software GL.
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  preview.Render(view, offscreen, studio_.design.selection());
  if (studio_.video.recording()) {
    // The view alone: read before the panels and the overlay go over it.
    try {
      studio_.video.Capture(view);
    } catch (const std::exception& e) {
      studio_.Refuse(std::string("video stopped: ") + e.what());
    }
  }
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

  if (studio_.layout.enabled()) {
    LayoutRecorder& layout = studio_.layout;
    layout.State("panel left", RectText(panels.left));
    layout.State("panel right", RectText(panels.right));
    layout.State("panel view", RectText(panels.view));
    layout.State("panel status", RectText(panels.status));
    char scale[32];
    std::snprintf(scale, sizeof(scale), "%.2f", studio_.panels.ui_scale);
    layout.State("ui scale", scale);
    layout.State("video", studio_.video.recording() ? "recording" : "stopped");
    const CameraFeed& feed = *studio_.camera_feed;
    layout.State("camera pictures", std::to_string(feed.rendered()));
    layout.State("camera seq", std::to_string(feed.picture().seq));
    layout.State("camera cameras", std::to_string(feed.cameras().size()));
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%.1f", studio_.video.seconds());
    layout.State("video seconds", seconds);
    if (!studio_.video.videos().empty()) {
      layout.State("video last", studio_.video.videos().back().path);
    }
  }
  if (studio_.layout.enabled()) RecordState(view, height);
}

void StudioApp::UpdatePreview() {
  LivePanel& live = *studio_.live;
  Preview& preview = *studio_.preview;
  const Design& design = studio_.design;
  // The preview follows the design: one rebuild per change. A live run of
  // another body (an optimisation's best) shows that body instead.
  const Scenario* replay = live.live_scenario();
  const Scenario& shown = replay ? *replay : design.scenario();
  const int shown_live = replay ? live.live_scenario_revision() : -1;
  if (design.revision() != studio_.built_revision ||
      shown_live != built_live_) {
    const auto start = std::chrono::steady_clock::now();
    // Another body, or back to the design after a run: the camera frames
    // it (a body may be twice the design; a followed run left it far off).
    if (shown_live != built_live_) preview.Reframe();
    studio_.build_error = preview.Rebuild(shown);
    preview.ShowDesign();
    CheckOverlaps(studio_, shown);
    studio_.oversized_meshes = design.OversizedMeshes();
    last_rebuild_ms_ = std::chrono::duration<double, std::milli>(
                           std::chrono::steady_clock::now() - start)
                           .count();
    studio_.built_revision = design.revision();
    built_live_ = shown_live;
  }

  // Live: the robots and objects where the running simulation has them.
  if (live.connected() && !live.session().robots().empty()) {
    std::map<std::string, RobotState> states;
    for (const LiveRobot* r : live.session().robots()) {
      if (r->states > 0) states[r->name] = FromRobotStateMessage(r->state);
    }
    std::vector<SceneObjectState> scene;
    if (live.session().scene()) {
      scene = FromSceneStateMessage(*live.session().scene());
    }
    preview.SetTracking(live.camera_follows());
    preview.ShowStates(shown, states,
                       live.session().scene() ? &scene : nullptr);
  } else if (preview.live()) {
    preview.ShowDesign();
  }
}

void StudioApp::UpdateCameraFeed() {
  Preview& preview = *studio_.preview;
  CameraFeed& feed = *studio_.camera_feed;
  const LivePanel& live = *studio_.live;
  if (!preview.has_model()) return;
  if (feed.key() != preview.builds()) {
    const Scenario* replay = live.live_scenario();
    feed.SetModel(preview.model(), replay ? *replay : studio_.design.scenario(),
                  preview.builds());
  }
  // Rendered only while the section shows it: a picture costs CPU.
  if (!live.camera_shown() || feed.cameras().empty()) return;
  // The time and state the view shows the camera's robot at; the design's
  // own pose is no state (-1) at 0 s.
  double sim_time = 0;
  std::int64_t seq = -1;
  // A camera on no robot (a scene object's) shows the run as the first
  // robot's newest state does.
  const ScenarioCamera& camera = feed.cameras()[feed.selected()];
  const Scenario* replay = live.live_scenario();
  const Scenario& shown = replay ? *replay : studio_.design.scenario();
  const std::string owner = camera.robot >= 0      ? camera.owner
                            : shown.robots.empty() ? std::string()
                                                   : RobotName(shown, 0);
  const LiveRobot* robot = preview.live() && live.connected()
                               ? live.session().robot(owner)
                               : nullptr;
  if (robot != nullptr && robot->states > 0) {
    sim_time = robot->state.sim_time;
    seq = robot->state.seq;
  }
  feed.Update(preview.data(), sim_time, seq);
}

void StudioApp::RecordState(const mjrRect& view, int height) {
  // State for tests and tools (--layout-dump).
  LayoutRecorder& layout = studio_.layout;
  const Selection& s = studio_.design.selection();
  layout.State("selected", std::string(ToString(s.kind)) + " " +
                               std::to_string(s.robot) + " " +
                               std::to_string(s.index));
  layout.State("dirty", studio_.design.dirty() ? "1" : "0");
  layout.State("path", studio_.design.path());
  layout.State("embed", studio_.embed_on_save ? "1" : "0");
  layout.State("revision", std::to_string(studio_.built_revision));
  layout.State("modal", studio_.ask_unsaved && unsaved_.shown() ? "unsaved"
                        : busy_quit_.shown()                    ? "busy"
                        : refusal_.shown()                      ? "refused"
                        : studio_.browser.is_open()             ? "file"
                        : studio_.show_template                 ? "template"
                                                                : "none");
  layout.State("message", studio_.message);
  layout.State("overlaps", std::to_string(studio_.overlaps.size()));
  layout.State("oversized meshes",
               std::to_string(studio_.oversized_meshes.size()));
  // Where ImGui has the mouse, so a test presses only once it is there.
  char mouse[64];
  std::snprintf(mouse, sizeof(mouse), "%.0f %.0f%s", ImGui::GetIO().MousePos.x,
                ImGui::GetIO().MousePos.y,
                ImGui::IsMouseDown(0) ? " down" : "");
  layout.State("mouse", mouse);
  for (const PartMarker& m : studio_.preview->Markers(view, height)) {
    char xy[64];
    std::snprintf(xy, sizeof(xy), "%.0f %.0f", m.x, m.y);
    layout.State("part " + std::string(ToString(m.part.kind)) + " " +
                     std::to_string(m.part.robot) + " " +
                     std::to_string(m.part.index),
                 xy);
  }
  layout.EndFrame();
}

void StudioApp::HandleKeys() {
  const bool typing = ImGui::GetIO().WantTextInput;
  const std::vector<std::pair<int, int>> keys = std::move(keys_);
  keys_.clear();
  for (const auto& [key, mods] : keys) {
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl && key == GLFW_KEY_Q) {
      studio_.RequestClose();
    } else if (typing) {
      continue;  // the text field has the keys
    } else if (key == GLFW_KEY_F5) {
      studio_.show_run = !studio_.show_run;
    } else if (key == GLFW_KEY_TAB && !ctrl) {
      // As MuJoCo's simulate: Tab the left panel, Shift+Tab the right.
      bool& shown =
          shift ? studio_.panels.show_right : studio_.panels.show_left;
      shown = !shown;
    } else if (key == GLFW_KEY_F11) {
      studio_.ToggleFullView();
    } else if (ctrl && key == GLFW_KEY_R) {
      studio_.ToggleVideo();
    } else if (studio_.show_run && studio_.live->OnKey(key)) {
      continue;  // arrows steer the running robot
    } else if (ctrl && key == GLFW_KEY_Z) {
      shift ? studio_.design.Redo() : studio_.design.Undo();
    } else if (ctrl && key == GLFW_KEY_Y) {
      studio_.design.Redo();
    } else if (ctrl && key == GLFW_KEY_S) {
      if (shift) {
        studio_.BrowseSaveAs();
      } else {
        studio_.SaveFile();
      }
    } else if (ctrl && key == GLFW_KEY_O) {
      studio_.Guard(Pending::kOpen);
    } else if (ctrl && key == GLFW_KEY_N) {
      studio_.Guard(Pending::kNew);
    } else if (key == GLFW_KEY_DELETE) {
      studio_.Try("remove the part", [&] { studio_.design.RemoveSelected(); });
    } else if (key == GLFW_KEY_F1) {
      studio_.show_help = !studio_.show_help;
    } else if (!ctrl && key == GLFW_KEY_F) {
      studio_.preview->FrameAll();
    }
  }
}

void StudioApp::HandlePanelEdges(const PanelLayout& panels, int width) {
  // A side panel's inner edge dragged sideways widens or narrows it.
  const ImGuiIO& io = ImGui::GetIO();
  const float scale = std::max(studio_.panels.ui_scale, 0.5f);
  const float x = io.MousePos.x, grab = 4 * scale;
  const bool on_left =
      panels.left.w > 0 && std::abs(x - panels.left.right()) <= grab;
  const bool on_right =
      panels.right.w > 0 && std::abs(x - panels.right.x) <= grab;
  const bool modal = ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId);
  if (resizing_ == 0 && !modal && ImGui::IsMouseClicked(0) &&
      io.MousePos.y >= 0 && (on_left || on_right)) {
    resizing_ = on_left ? 1 : 2;
  }
  if (resizing_ != 0 && !ImGui::IsMouseDown(0)) resizing_ = 0;
  if (resizing_ != 0 || ((on_left || on_right) && !modal)) {
    ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeEW);
  }
  const float widest = std::max(kMinPanelWidth, width * 0.6f / scale);
  if (resizing_ == 1) {
    studio_.panels.left_width = std::clamp(x / scale, kMinPanelWidth, widest);
  } else if (resizing_ == 2) {
    studio_.panels.right_width =
        std::clamp((width - x) / scale, kMinPanelWidth, widest);
  }
}

void StudioApp::HandleViewInput(const mjrRect& view, float left, float top) {
  bool& dragging = view_drag_;
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 p = io.MousePos;
  const bool inside = p.x >= left && p.x < left + view.width && p.y >= top &&
                      p.y < top + view.height;
  // The handles first: a press on one moves the part, not the camera.
  if (handles_.Update(studio_, view, static_cast<int>(top) + view.height)) {
    return;
  }
  if ((io.WantCaptureMouse || resizing_ != 0) && !dragging) return;
  const double h = view.height;
  if (inside && io.MouseWheel != 0)
    studio_.preview->Zoom(-0.05 * io.MouseWheel);
  const bool clicked = ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1);
  if (inside && clicked) dragging = true;
  if (!dragging) return;
  // The frame of the press carries the jump to where it happened: no drag.
  const double dx = io.MouseDelta.x / h, dy = io.MouseDelta.y / h;
  const bool pan =
      ImGui::IsMouseDown(1) || (ImGui::IsMouseDown(0) && io.KeyShift);
  if (!clicked && pan) {
    studio_.preview->Pan(dx, dy);
  } else if (!clicked && ImGui::IsMouseDown(0)) {
    studio_.preview->Orbit(dx, dy);
  }
  if (ImGui::IsMouseReleased(0) && io.MouseDragMaxDistanceSqr[0] < 16) {
    studio_.design.Select(studio_.preview->Pick(view, p.x - left, p.y - top));
  }
  if (!ImGui::IsMouseDown(0) && !ImGui::IsMouseDown(1)) dragging = false;
}

}  // namespace mrsim::studio
