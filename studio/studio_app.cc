#include "studio/studio_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "launcher/program_locator.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/part_look.h"
#include "sim_core/scenario_xml.h"
#include "sim_core/sensor_face.h"
#include "studio/chain_edit.h"
#include "studio/gui_setup.h"
#include "studio/inspector_fields.h"

namespace mrsim::studio {
namespace {

// A dialog of fixed size (height 0: as its text needs), centred across
// the window at height `top`: where a modal is expected, never dragged off.
bool BeginFixedModal(const char* title, float width, float height, float top) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x / 2 - width / 2, top));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  return ImGui::BeginPopupModal(
      title, nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
}

constexpr float kLeftWidth = 330;
constexpr float kRightWidth = 400;
constexpr float kStatusHeight = 30;
constexpr ImGuiWindowFlags kPanelFlags =
    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
    ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
    ImGuiWindowFlags_NoBringToFrontOnFocus;

// A tooltip for a message too long for its line, wrapped to a readable
// width instead of running off the window.
void WrappedTooltip(const std::string& text) {
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

std::string Key(const Selection& s, const std::string& sub,
                const std::string& field) {
  return std::string(ToString(s.kind)) + " " + std::to_string(s.robot) + " " +
         std::to_string(s.index) + "/" + sub + "/" + field;
}

std::string LimitsText(const FieldInfo& info) {
  const FieldLimits& l = info.limits;
  char buf[96] = "";
  if (std::isfinite(l.min) && std::isfinite(l.max)) {
    std::snprintf(buf, sizeof(buf), "%g .. %g", l.min, l.max);
  } else if (std::isfinite(l.min)) {
    std::snprintf(buf, sizeof(buf), "%s %g",
                  l.min_exclusive ? ">" : ">=", l.min);
  }
  return buf;
}

// The colour the preview shows a kind of part in (the MJCF look's hue).
ImVec4 Swatch(Look look) {
  PartLook kind = PartLook::kLooseFrame;
  switch (look) {
    case Look::kPitchModule:
      kind = PartLook::kPitchModule;
      break;
    case Look::kYawModule:
      kind = PartLook::kYawModule;
      break;
    case Look::kSensorModule:
      kind = PartLook::kSensorModule;
      break;
    case Look::kForcePlate:
      kind = PartLook::kForcePlate;
      break;
    case Look::kDistanceSensor:
      kind = PartLook::kDistanceSensor;
      break;
    case Look::kObject:
      kind = PartLook::kSceneObject;
      break;
    default:
      break;
  }
  const Eigen::Vector3d c = PartLookRgb(kind);
  return ImVec4(static_cast<float>(c.x()), static_cast<float>(c.y()),
                static_cast<float>(c.z()), 1.0f);
}

}  // namespace

StudioApp::StudioApp(Design design, const AppOptions& options)
    : design_(std::move(design)),
      options_(options),
      preview_(std::make_unique<Preview>(options.width, options.height)),
      layout_(options.layout_dump),
      live_(std::make_unique<LivePanel>(ProgramSearchPath(""), &layout_)),
      recent_(options.recent_store) {
  // Before any OpenGL context: every shell makes its context after this.
  PreferOneSoftwareRenderThread();
  template_.chain.modules = 5;
  template_.chain.pattern = ChainPattern::kPitchYaw;
  Note(design_.note());
  if (!design_.path().empty() && std::filesystem::exists(design_.path())) {
    recent_.Add(design_.path());
  }
}

StudioApp::~StudioApp() = default;

bool StudioApp::Button(const char* label, float width) {
  const bool pressed = ImGui::Button(label, ImVec2(width, 0));
  Record(label);
  return pressed;
}

void StudioApp::Record(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin();
  const ImVec2 b = ImGui::GetItemRectMax();
  layout_.Widget(name, a.x, a.y, b.x - a.x, b.y - a.y);
  // Which field takes typed text: a test types only once it is this one.
  if (ImGui::IsItemActive()) layout_.State("active", name);
}

void StudioApp::Try(const std::function<void()>& edit) {
  try {
    edit();
    message_.clear();
  } catch (const ScenarioError& e) {
    // The design's own words, without the XML path of the part: the
    // inspector already shows which part is selected.
    Refuse(e.message().empty() ? e.what() : e.message());
  } catch (const std::exception& e) {
    Refuse(e.what());
  }
}

void StudioApp::Try(const std::string& action,
                    const std::function<void()>& edit) {
  Try(edit);
  if (message_is_error_ && !message_.empty()) {
    refused_action_ = action;
    refused_why_ = message_;
  }
}

void StudioApp::DrawRefusalDialog() {
  if (refused_action_.empty()) return;
  ImGui::OpenPopup("Not done");
  if (!BeginFixedModal("Not done", 460, 0, ImGui::GetIO().DisplaySize.y / 3)) {
    return;
  }
  refused_shown_ = !ImGui::IsWindowAppearing();
  ImGui::TextWrapped("Could not %s:", refused_action_.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.75f, 0.3f, 1));
  ImGui::TextWrapped("%s", refused_why_.c_str());
  ImGui::PopStyleColor();
  const bool ok = ImGui::Button("OK", ImVec2(120, 0)) ||
                  ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
                  ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
  Record("refused OK");
  if (ok) {
    refused_action_.clear();
    refused_shown_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void StudioApp::Note(const std::string& text) {
  message_ = text;
  message_is_error_ = false;
}

void StudioApp::Refuse(const std::string& text) {
  message_ = text;
  message_is_error_ = true;
}

void StudioApp::Frame(int width, int height, bool offscreen) {
  ImGui::NewFrame();
  layout_.BeginFrame();
  HandleKeys();

  live_->Poll();
  DrawDesignPanel(0, 0, kLeftWidth, static_cast<float>(height));
  if (show_run_) {
    LiveDesign live;
    live.path = design_.path();
    live.dirty = design_.dirty();
    for (const Robot& r : design_.scenario().robots) {
      live.robots.push_back(r.name);
    }
    live.save = [this] {
      SaveFile();
      return design_.dirty() ? std::string() : design_.path();
    };
    live_->Draw(width - kRightWidth, 0, kRightWidth, static_cast<float>(height),
                live);
  } else {
    DrawInspector(width - kRightWidth, 0, kRightWidth,
                  static_cast<float>(height));
  }
  DrawStatus(kLeftWidth, 0, width - kLeftWidth - kRightWidth);
  live_->DrawOverlay(kLeftWidth + 8, kStatusHeight + 8);
  DrawDialogs();
  if (show_help_) DrawHelp();

  const mjrRect view = {
      static_cast<int>(kLeftWidth), 0,
      std::max(16, width - static_cast<int>(kLeftWidth + kRightWidth)),
      std::max(16, height - static_cast<int>(kStatusHeight))};
  HandleViewInput(view, kLeftWidth, kStatusHeight);

  // The preview follows the design: one rebuild per change. A live run of
  // another body (an optimisation's best) shows that body instead.
  const Scenario* replay = live_->live_scenario();
  const Scenario& shown = replay ? *replay : design_.scenario();
  const int shown_live = replay ? live_->live_scenario_revision() : -1;
  if (design_.revision() != built_revision_ || shown_live != built_live_) {
    const auto start = std::chrono::steady_clock::now();
    // Another body, or back to the design after a run: the camera frames
    // it (a body may be twice the design; a followed run left it far off).
    if (shown_live != built_live_) preview_->Reframe();
    build_error_ = preview_->Rebuild(shown);
    preview_->ShowDesign();
    last_rebuild_ms_ = std::chrono::duration<double, std::milli>(
                           std::chrono::steady_clock::now() - start)
                           .count();
    built_revision_ = design_.revision();
    built_live_ = shown_live;
  }

  // Live: the robots and objects where the running simulation has them.
  if (live_->connected() && !live_->session().robots().empty()) {
    std::map<std::string, RobotState> states;
    for (const LiveRobot* r : live_->session().robots()) {
      if (r->states > 0) states[r->name] = FromRobotStateMessage(r->state);
    }
    std::vector<SceneObjectState> scene;
    if (live_->session().scene()) {
      scene = FromSceneStateMessage(*live_->session().scene());
    }
    preview_->SetTracking(live_->camera_follows());
    preview_->ShowStates(shown, states,
                         live_->session().scene() ? &scene : nullptr);
  } else if (preview_->live()) {
    preview_->ShowDesign();
  }

  ImGui::Render();
  // Clear the whole frame, then the 3-D view, then the panels over it.
  preview_->Bind(offscreen);
  glViewport(0, 0, width, height);
  glClearColor(0.12f, 0.13f, 0.15f, 1.0f);
  glDisable(GL_SCISSOR_TEST);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  preview_->Render(view, offscreen, design_.selection());
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

  // State for tests and tools (--layout-dump).
  if (layout_.enabled()) {
    const Selection& s = design_.selection();
    layout_.State("selected", std::string(ToString(s.kind)) + " " +
                                  std::to_string(s.robot) + " " +
                                  std::to_string(s.index));
    layout_.State("dirty", design_.dirty() ? "1" : "0");
    layout_.State("path", design_.path());
    layout_.State("revision", std::to_string(built_revision_));
    layout_.State("modal", ask_unsaved_ && unsaved_shown_ ? "unsaved"
                           : busy_quit_shown_             ? "busy"
                           : refused_shown_               ? "refused"
                           : browser_.is_open()           ? "file"
                           : show_template_               ? "template"
                                                          : "none");
    layout_.State("message", message_);
    for (const PartMarker& m : preview_->Markers(view, height)) {
      char xy[64];
      std::snprintf(xy, sizeof(xy), "%.0f %.0f", m.x, m.y);
      layout_.State("part " + std::string(ToString(m.part.kind)) + " " +
                        std::to_string(m.part.robot) + " " +
                        std::to_string(m.part.index),
                    xy);
    }
    layout_.EndFrame();
  }
}

void StudioApp::HandleKeys() {
  const bool typing = ImGui::GetIO().WantTextInput;
  const std::vector<std::pair<int, int>> keys = std::move(keys_);
  keys_.clear();
  for (const auto& [key, mods] : keys) {
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (ctrl && key == GLFW_KEY_Q) {
      RequestClose();
    } else if (typing) {
      continue;  // the text field has the keys
    } else if (key == GLFW_KEY_F5) {
      show_run_ = !show_run_;
    } else if (show_run_ && live_->OnKey(key)) {
      continue;  // arrows steer the running robot
    } else if (ctrl && key == GLFW_KEY_Z) {
      shift ? design_.Redo() : design_.Undo();
    } else if (ctrl && key == GLFW_KEY_Y) {
      design_.Redo();
    } else if (ctrl && key == GLFW_KEY_S) {
      if (shift) {
        browse_for_ = BrowseFor::kSaveAs;
        browser_.Open("Save scenario as", StartFolder(), ".xml", true);
      } else {
        SaveFile();
      }
    } else if (ctrl && key == GLFW_KEY_O) {
      Guard(Pending::kOpen);
    } else if (ctrl && key == GLFW_KEY_N) {
      Guard(Pending::kNew);
    } else if (key == GLFW_KEY_DELETE) {
      Try("remove the part", [&] { design_.RemoveSelected(); });
    } else if (key == GLFW_KEY_F1) {
      show_help_ = !show_help_;
    } else if (!ctrl && key == GLFW_KEY_F) {
      preview_->FrameAll();
    }
  }
}

void StudioApp::HandleViewInput(const mjrRect& view, float left, float top) {
  bool& dragging = view_drag_;
  const ImGuiIO& io = ImGui::GetIO();
  const ImVec2 p = io.MousePos;
  const bool inside = p.x >= left && p.x < left + view.width && p.y >= top &&
                      p.y < top + view.height;
  if (io.WantCaptureMouse && !dragging) return;
  const double h = view.height;
  if (inside && io.MouseWheel != 0) preview_->Zoom(-0.05 * io.MouseWheel);
  const bool clicked = ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1);
  if (inside && clicked) dragging = true;
  if (!dragging) return;
  // The frame of the press carries the jump to where it happened: no drag.
  const double dx = io.MouseDelta.x / h, dy = io.MouseDelta.y / h;
  const bool pan =
      ImGui::IsMouseDown(1) || (ImGui::IsMouseDown(0) && io.KeyShift);
  if (!clicked && pan) {
    preview_->Pan(dx, dy);
  } else if (!clicked && ImGui::IsMouseDown(0)) {
    preview_->Orbit(dx, dy);
  }
  if (ImGui::IsMouseReleased(0) && io.MouseDragMaxDistanceSqr[0] < 16) {
    design_.Select(preview_->Pick(view, p.x - left, p.y - top));
  }
  if (!ImGui::IsMouseDown(0) && !ImGui::IsMouseDown(1)) dragging = false;
}

void StudioApp::Guard(Pending action) {
  pending_ = action;
  if (design_.dirty() && action != Pending::kTemplate) {
    ask_unsaved_ = true;
  } else {
    RunPending();
  }
}

void StudioApp::RunPending() {
  const Pending action = pending_;
  pending_ = Pending::kNone;
  switch (action) {
    case Pending::kNew:
      design_ = Design();
      built_revision_ = -1;
      message_.clear();
      break;
    case Pending::kOpen:
      browse_for_ = BrowseFor::kOpen;
      browser_.Open("Open scenario", StartFolder(), ".xml", false);
      break;
    case Pending::kTemplate:
      show_template_ = true;
      break;
    case Pending::kQuit:
      quit_ = true;
      break;
    case Pending::kNone:
      break;
  }
}

void StudioApp::RequestClose() {
  const std::vector<std::string> busy = live_->InProgress();
  if (busy.empty()) {
    Guard(Pending::kQuit);
    return;
  }
  std::string words;
  for (size_t i = 0; i < busy.size(); ++i) {
    words += (i == 0 ? "" : i + 1 == busy.size() ? " and " : ", ") + busy[i];
  }
  words[0] = static_cast<char>(std::toupper(words[0]));
  const bool one = busy.size() == 1;
  ask_busy_quit_ = words + (one ? " is" : " are") +
                   " going on. Quitting stops " + (one ? "it." : "them.");
  const auto has = [&](const char* what) {
    return std::find(busy.begin(), busy.end(), what) != busy.end();
  };
  if (has("a recording")) ask_busy_quit_ += " The recorded files are kept.";
  if (has("an optimisation")) {
    ask_busy_quit_ +=
        " The optimisation continues from its last generation when started "
        "again.";
  }
}

void StudioApp::OpenFile(const std::string& path) {
  try {
    design_ = Design::Open(path);
    built_revision_ = -1;
    recent_.Add(path);
    Note(design_.note());
    preview_->Reframe();
  } catch (const std::exception& e) {
    Refuse(e.what());
  }
}

std::string StudioApp::StartFolder() const {
  if (!design_.path().empty()) {
    return std::filesystem::path(design_.path()).parent_path().string();
  }
  std::error_code ec;
  return std::filesystem::is_directory("scenarios", ec) ? "scenarios" : ".";
}

void StudioApp::SaveFile() {
  if (design_.path().empty()) {
    browse_for_ = BrowseFor::kSaveAs;
    browser_.Open("Save scenario as", StartFolder(), ".xml", true);
    return;
  }
  try {
    design_.Save();
    recent_.Add(design_.path());
    Note("saved " + design_.path());
  } catch (const std::exception& e) {
    Refuse(e.what());
  }
}

void StudioApp::DrawDesignPanel(float x, float y, float w, float h) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  ImGui::Begin("Design", nullptr, kPanelFlags);
  const float third = (w - 32) / 3;
  if (Button("New", third / 1.5f)) Guard(Pending::kNew);
  ImGui::SameLine();
  if (Button("Open", third / 1.5f)) Guard(Pending::kOpen);
  ImGui::SameLine();
  if (Button("Save", third / 1.5f)) SaveFile();
  ImGui::SameLine();
  if (Button("Save As", third / 1.5f + 4)) {
    browse_for_ = BrowseFor::kSaveAs;
    browser_.Open("Save scenario as", StartFolder(), ".xml", true);
  }
  if (Button("Undo", third)) design_.Undo();
  ImGui::SameLine();
  if (Button("Redo", third)) design_.Redo();
  ImGui::SameLine();
  if (Button("Help (F1)", third)) show_help_ = !show_help_;
  if (Button("New robot from template...", -1)) Guard(Pending::kTemplate);
  if (!recent_.paths().empty() && ImGui::CollapsingHeader("Recent files")) {
    for (const std::string& p : recent_.paths()) {
      if (ImGui::Selectable(p.c_str())) {
        pending_path_ = p;
        if (design_.dirty()) {
          pending_ = Pending::kOpen;
          ask_unsaved_ = true;
        } else {
          OpenFile(p);
        }
      }
    }
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Next part");
  int where = static_cast<int>(where_);
  ImGui::RadioButton("after selected", &where, 0);
  ImGui::SameLine();
  ImGui::RadioButton("front", &where, 1);
  ImGui::SameLine();
  ImGui::RadioButton("tail", &where, 2);
  where_ = static_cast<Where>(where);
  const struct {
    const char* label;
    NextPart part;
    Look look;
  } parts[] = {{"pitch module", NextPart::kPitchModule, Look::kPitchModule},
               {"yaw module", NextPart::kYawModule, Look::kYawModule},
               {"sensor module", NextPart::kSensorModule, Look::kSensorModule}};
  for (const auto& p : parts) {
    ImGui::PushStyleColor(ImGuiCol_Button, Swatch(p.look));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0, 0, 0, 1));
    if (Button(p.label, third)) {
      Try(std::string("add the ") + p.label,
          [&] { design_.AddPart(p.part, where_); });
    }
    ImGui::PopStyleColor(2);
    if (&p != &parts[2]) ImGui::SameLine();
  }

  // The chain, front to back. Rows are written in their part's colour, so
  // the selection is marked in grey: ImGui's blue would hide a blue yaw
  // row.
  ImGui::BeginChild("parts", ImVec2(0, h * 0.28f), true);
  ImGui::PushStyleColor(ImGuiCol_Header, ImVec4(0.32f, 0.33f, 0.36f, 1));
  ImGui::PushStyleColor(ImGuiCol_HeaderHovered, ImVec4(0.25f, 0.26f, 0.28f, 1));
  ImGui::PushStyleColor(ImGuiCol_HeaderActive, ImVec4(0.40f, 0.41f, 0.44f, 1));
  const Scenario& s = design_.scenario();
  for (int r = 0; r < static_cast<int>(s.robots.size()); ++r) {
    const Robot& robot = s.robots[r];
    const Selection robot_sel{PartKind::kRobot, r, 0};
    if (ImGui::Selectable(("robot " + robot.name).c_str(),
                          design_.selection() == robot_sel)) {
      design_.Select(robot_sel);
    }
    for (const ChainSlot& slot : ChainOrder(robot)) {
      const Selection sel{
          slot.sensor ? PartKind::kSensorModule : PartKind::kModule, r,
          slot.source};
      std::string label;
      Look look;
      if (slot.sensor) {
        const SensorModule& sm = robot.sensor_modules[slot.source];
        label = "  S" + std::to_string(slot.source) + "  sensor module" +
                (sm.force_sensor ? " +plate" : "") +
                (sm.distance_sensors.empty() ? "" : " +ray");
        look = Look::kSensorModule;
      } else {
        label = "  " + std::to_string(slot.source) + "  " +
                (slot.axis == Axis::kPitch ? "pitch" : "yaw") + " module";
        look =
            slot.axis == Axis::kPitch ? Look::kPitchModule : Look::kYawModule;
      }
      ImGui::PushStyleColor(ImGuiCol_Text, Swatch(look));
      if (ImGui::Selectable(label.c_str(), design_.selection() == sel)) {
        design_.Select(sel);
      }
      ImGui::PopStyleColor();
      Record("row " + std::string(ToString(sel.kind)) + " " +
             std::to_string(r) + " " + std::to_string(sel.index));
    }
  }
  if (s.robots.empty()) {
    ImGui::TextWrapped("No robot yet: add a pitch or yaw module.");
  }
  ImGui::PopStyleColor(3);
  ImGui::EndChild();
  if (Button("Move to front", third)) {
    Try("move the part to the front", [&] { design_.MoveSelected(-1); });
  }
  ImGui::SameLine();
  if (Button("Move to back", third)) {
    Try("move the part to the back", [&] { design_.MoveSelected(1); });
  }
  ImGui::SameLine();
  if (Button("Remove", third)) {
    Try("remove the part", [&] { design_.RemoveSelected(); });
  }

  ImGui::Separator();
  ImGui::TextUnformatted("Add object (in front of the robot)");
  const struct {
    const char* label;
    ObjectKind kind;
  } objects[] = {{"ball", ObjectKind::kBall},
                 {"box", ObjectKind::kBox},
                 {"cylinder", ObjectKind::kCylinder},
                 {"capsule", ObjectKind::kCapsule},
                 {"ramp", ObjectKind::kRamp}};
  const float fifth = (w - 40) / 5;
  for (const auto& o : objects) {
    if (Button(o.label, fifth)) {
      Try(std::string("add a ") + o.label, [&] { design_.AddObject(o.kind); });
    }
    if (&o != &objects[4]) ImGui::SameLine();
  }
  for (int i = 0; i < static_cast<int>(s.scene_objects.size()); ++i) {
    const Selection sel{PartKind::kObject, 0, i};
    const SceneObject& o = s.scene_objects[i];
    ImGui::PushStyleColor(ImGuiCol_Text, Swatch(Look::kObject));
    if (ImGui::Selectable(
            ("  " + o.guid + " (" + ToString(o.shape) + ")").c_str(),
            design_.selection() == sel)) {
      design_.Select(sel);
    }
    ImGui::PopStyleColor();
  }

  ImGui::Separator();
  ImGui::TextUnformatted("World");
  if (Button("Terrain", third)) design_.Select({PartKind::kScene, 0, 0});
  ImGui::SameLine();
  if (Button("flat ground", third)) {
    Try([&] {
      design_.SetTerrain("", 0.0, design_.scenario().scene.meters_per_pixel);
    });
  }
  ImGui::SameLine();
  if (Button("height image...", third)) {
    browse_for_ = BrowseFor::kHeightImage;
    browser_.Open("Height image (grey PNG)", StartFolder(), ".png", false);
  }
  if (Button("water", third)) {
    Try("add water", [&] { design_.AddFluid(FluidKind::kWater); });
  }
  ImGui::SameLine();
  if (Button("air", third)) {
    Try("add air", [&] { design_.AddFluid(FluidKind::kAir); });
  }
  ImGui::SameLine();
  if (Button("contact pair", third)) {
    Try("add a contact pair", [&] { design_.AddContact(); });
  }
  for (int i = 0; i < static_cast<int>(s.fluid_regions.size()); ++i) {
    const Selection sel{PartKind::kFluid, 0, i};
    if (ImGui::Selectable(("  " + s.fluid_regions[i].guid).c_str(),
                          design_.selection() == sel)) {
      design_.Select(sel);
    }
  }
  for (int i = 0; i < static_cast<int>(s.contact_frictions.size()); ++i) {
    const Selection sel{PartKind::kContact, 0, i};
    const ContactFriction& c = s.contact_frictions[i];
    if (ImGui::Selectable(("  contact " + c.material1 + " / " + c.material2 +
                           "##" + std::to_string(i))
                              .c_str(),
                          design_.selection() == sel)) {
      design_.Select(sel);
    }
  }
  if (Button("Simulation settings", -1)) {
    design_.Select({PartKind::kSettings, 0, 0});
  }
  ImGui::End();
}

void StudioApp::DrawInspector(float x, float y, float w, float h) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  ImGui::Begin("Inspector", nullptr, kPanelFlags);
  Scenario view = design_.scenario();
  const Selection sel = design_.selection();
  if (design_.revision() != fields_revision_ || sel != fields_selection_) {
    // What was refused belongs to the design and part it was typed for.
    field_errors_.clear();
    field_edits_.clear();
    fields_revision_ = design_.revision();
    fields_selection_ = sel;
  }
  const std::vector<FieldGroup> groups = InspectorFields(view, sel);
  if (groups.empty()) {
    ImGui::TextWrapped(
        "Select a part in the list or click it in the 3-D view to see and "
        "edit every field.");
  }
  if (sel.kind == PartKind::kSensorModule) DrawSensorMounts(view, sel);
  for (const FieldGroup& g : groups) {
    if (!ImGui::CollapsingHeader(g.title.c_str(),
                                 ImGuiTreeNodeFlags_DefaultOpen)) {
      continue;
    }
    ImGui::PushID(g.sub.c_str());
    for (const FieldRef& f : g.fields) {
      const FieldInfo& info = f.info();
      const std::string key = Key(sel, g.sub, info.xml);
      const FieldAddress address{sel, g.sub, info.xml};
      std::string label = info.xml;
      if (*info.unit) label += std::string(" [") + info.unit + "]";
      ImGui::PushID(info.xml);
      ImGui::TextUnformatted(label.c_str());
      if (ImGui::IsItemHovered()) {
        const std::string limits = LimitsText(info);
        ImGui::SetTooltip("%s%s%s", info.help,
                          limits.empty() ? "" : "\nlimits: ", limits.c_str());
      }
      ImGui::SameLine(w * 0.5f);
      ImGui::SetNextItemWidth(-1);
      const bool numbers = f.type() == FieldType::kNumber ||
                           f.type() == FieldType::kVector ||
                           f.type() == FieldType::kQuaternion;
      const std::string current =
          numbers ? ShortNumbers(f.GetText()) : f.GetText();
      if (*info.limits.meaning) {
        // An integer range whose values have names (a face): picked by
        // name, from the schema's own list.
        std::vector<std::string> names;
        std::stringstream meaning(info.limits.meaning);
        for (std::string n; std::getline(meaning, n, ',');) {
          names.push_back(n.substr(n.find_first_not_of(' ')));
        }
        const int value = std::atoi(current.c_str());
        const auto name_of = [&](int k) {
          const int i = k - static_cast<int>(info.limits.min);
          return std::to_string(k) +
                 (i >= 0 && i < static_cast<int>(names.size()) ? " " + names[i]
                                                               : "");
        };
        if (ImGui::BeginCombo("##v", name_of(value).c_str())) {
          for (int k = static_cast<int>(info.limits.min);
               k <= static_cast<int>(info.limits.max); ++k) {
            if (ImGui::Selectable(name_of(k).c_str(), k == value)) {
              Try([&] { design_.SetField(address, std::to_string(k)); });
            }
          }
          ImGui::EndCombo();
        }
      } else if (info.kept) {
        ImGui::TextDisabled("%s", current.c_str());
      } else if (f.type() == FieldType::kBool) {
        bool on = current == "true";
        if (ImGui::Checkbox("##v", &on)) {
          Try([&] { design_.SetField(address, on ? "true" : "false"); });
        }
      } else if (f.type() == FieldType::kChoice) {
        if (ImGui::BeginCombo("##v", current.c_str())) {
          for (const std::string& c : f.choices()) {
            if (ImGui::Selectable(c.c_str(), c == current)) {
              Try([&] { design_.SetField(address, c); });
            }
          }
          ImGui::EndCombo();
        }
      } else {
        auto edit = field_edits_.find(key);
        std::string text = edit != field_edits_.end() ? edit->second : current;
        const bool enter = ImGui::InputText(
            "##v", &text, ImGuiInputTextFlags_EnterReturnsTrue);
        const bool active = ImGui::IsItemActive();
        if (active) {
          field_edits_[key] = text;
          // Checked as typed against the schema on a scratch copy.
          try {
            f.SetText(text);
            field_errors_.erase(key);
          } catch (const std::exception& e) {
            field_errors_[key] = e.what();
          }
        }
        if (enter || ImGui::IsItemDeactivatedAfterEdit()) {
          // Refused: the field shows the design's value again, so what is
          // on screen is what is saved and run.
          field_edits_.erase(key);
          try {
            design_.SetField(address, text);
            field_errors_.erase(key);
          } catch (const std::exception& e) {
            field_errors_[key] =
                "not applied, still " + current + ": " + e.what();
          }
        } else if (!active && field_edits_.erase(key) > 0) {
          field_errors_.erase(key);  // typing abandoned (Escape)
        }
      }
      Record("field " + g.sub + "/" + info.xml);
      auto error = field_errors_.find(key);
      if (error != field_errors_.end()) {
        ImGui::PushTextWrapPos(0);
        ImGui::TextColored(ImVec4(1, 0.35f, 0.35f, 1), "%s",
                           error->second.c_str());
        ImGui::PopTextWrapPos();
      }
      ImGui::PopID();
    }
    ImGui::PopID();
  }
  ImGui::End();
}

void StudioApp::DrawSensorMounts(const Scenario& view, const Selection& sel) {
  const SensorModule& sm =
      view.robots.at(sel.robot).sensor_modules.at(sel.index);
  bool plate = sm.force_sensor.has_value();
  if (ImGui::Checkbox("force plate", &plate)) {
    Try(plate ? "add the force plate" : "remove the force plate",
        [&] { design_.SetForcePlate(plate); });
  }
  Record("force plate");
  if (design_.revision() != ray_face_revision_ ||
      !(sel == ray_face_selection_)) {
    ray_face_revision_ = design_.revision();
    ray_face_selection_ = sel;
    const std::vector<int> open = design_.OpenRayFaces();
    // Front first (a sensor looking ahead), else the first face open.
    if (!open.empty() &&
        std::find(open.begin(), open.end(), ray_face_) == open.end()) {
      ray_face_ = std::find(open.begin(), open.end(), 4) != open.end()
                      ? 4
                      : open.front();
    }
  }
  ImGui::SetNextItemWidth(90);
  ImGui::Combo("##face", &ray_face_, kSensorFaceNames.data(),
               static_cast<int>(kSensorFaceNames.size()));
  ImGui::SameLine();
  if (Button("add distance sensor")) {
    Try("add the distance sensor",
        [&] { design_.AddDistanceSensor(ray_face_); });
  }
  for (size_t k = 0; k < sm.distance_sensors.size(); ++k) {
    const int face = sm.distance_sensors[k].sensor_position;
    ImGui::PushID(static_cast<int>(k));
    ImGui::Text("ray %zu: %s", k,
                face >= 0 && face < static_cast<int>(kSensorFaceNames.size())
                    ? kSensorFaceNames[face]
                    : "?");
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) {
      Try([&] { design_.RemoveDistanceSensor(static_cast<int>(k)); });
    }
    ImGui::PopID();
  }
  ImGui::Separator();
}

void StudioApp::DrawStatus(float x, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, kStatusHeight));
  ImGui::Begin(
      "status", nullptr,
      kPanelFlags | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
  const std::string name =
      design_.path().empty()
          ? std::string("untitled")
          : std::filesystem::path(design_.path()).filename().string();
  ImGui::Text("%s%s", name.c_str(), design_.dirty() ? " *" : "");
  ImGui::SameLine();
  if (Button(show_run_ ? "Inspector (F5)" : "Run panel (F5)")) {
    show_run_ = !show_run_;
  }
  ImGui::SameLine();
  if (!build_error_.empty()) {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "preview: %s",
                       build_error_.c_str());
    // One line is often too short for an error naming a file and field.
    if (ImGui::IsItemHovered()) WrappedTooltip(build_error_);
  } else if (!message_.empty()) {
    if (message_is_error_) {
      ImGui::TextColored(ImVec4(1, 0.75f, 0.3f, 1), "%s", message_.c_str());
    } else {
      ImGui::TextUnformatted(message_.c_str());
    }
    if (ImGui::IsItemHovered()) WrappedTooltip(message_);
  } else {
    // What fits beside the file name in the narrowest layout; the rest on
    // hover.
    ImGui::TextDisabled("drag: orbit  right-drag: pan  wheel: zoom  F: frame");
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "drag: orbit, right-drag (or shift+drag): pan, wheel: zoom\n"
          "F: frame the whole scene, click: select a part\nF1: help");
    }
  }
  ImGui::End();
}

void StudioApp::DrawDialogs() {
  std::string chosen;
  if (browser_.Draw(&chosen, &layout_)) {
    switch (browse_for_) {
      case BrowseFor::kOpen:
        OpenFile(chosen);
        break;
      case BrowseFor::kSaveAs:
        try {
          design_.SaveAs(chosen);
          recent_.Add(chosen);
          Note("saved " + chosen);
          if (pending_ != Pending::kNone) RunPending();
        } catch (const std::exception& e) {
          Refuse(e.what());
        }
        break;
      case BrowseFor::kHeightImage:
        Try([&] {
          const Scene& scene = design_.scenario().scene;
          design_.SetTerrain(chosen, scene.height > 0 ? scene.height : 0.3,
                             scene.meters_per_pixel);
        });
        break;
      case BrowseFor::kNone:
        break;
    }
    browse_for_ = BrowseFor::kNone;
  }
  if (ask_unsaved_) {
    ImGui::OpenPopup("Unsaved changes");
  }
  if (BeginFixedModal("Unsaved changes", 360, 90,
                      ImGui::GetIO().DisplaySize.y / 2 - 45)) {
    // Reported (for tests) once it takes clicks: not on its first frame.
    unsaved_shown_ = !ImGui::IsWindowAppearing();
    ImGui::TextWrapped("The design has unsaved changes. Save them first?");
    const bool save = ImGui::Button("Save", ImVec2(100, 0));
    Record("unsaved Save");
    if (save) {
      ask_unsaved_ = false;
      ImGui::CloseCurrentPopup();
      if (design_.path().empty()) {
        SaveFile();  // Save As first; the pending action follows it
      } else {
        SaveFile();
        if (!design_.dirty()) RunPending();
      }
    }
    ImGui::SameLine();
    const bool discard = ImGui::Button("Discard", ImVec2(100, 0));
    Record("unsaved Discard");
    if (discard) {
      ask_unsaved_ = false;
      ImGui::CloseCurrentPopup();
      if (pending_ == Pending::kOpen && !pending_path_.empty()) {
        pending_ = Pending::kNone;
        OpenFile(pending_path_);
        pending_path_.clear();
      } else {
        RunPending();
      }
    }
    ImGui::SameLine();
    const bool cancel = ImGui::Button("Cancel", ImVec2(100, 0));
    Record("unsaved Cancel");
    if (cancel) {
      ask_unsaved_ = false;
      pending_ = Pending::kNone;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
  if (show_template_) DrawTemplateDialog();
  DrawBusyQuitDialog();
  DrawRefusalDialog();
}

void StudioApp::DrawBusyQuitDialog() {
  if (ask_busy_quit_.empty()) return;
  ImGui::OpenPopup("Quit while running?");
  if (!BeginFixedModal("Quit while running?", 420, 0,
                       ImGui::GetIO().DisplaySize.y / 2 - 60)) {
    return;
  }
  busy_quit_shown_ = !ImGui::IsWindowAppearing();
  ImGui::TextWrapped("%s", ask_busy_quit_.c_str());
  const bool quit = ImGui::Button("Stop and quit", ImVec2(190, 0));
  Record("busy Quit");
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel", ImVec2(190, 0));
  Record("busy Cancel");
  if (quit || cancel) {
    ask_busy_quit_.clear();
    busy_quit_shown_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  if (quit) Guard(Pending::kQuit);  // unsaved changes are asked next
}

void StudioApp::DrawTemplateDialog() {
  ImGui::OpenPopup("New robot from template");
  if (!BeginFixedModal("New robot from template", 460, 480,
                       ImGui::GetIO().DisplaySize.y / 2 - 240)) {
    return;
  }
  ChainOptions& c = template_.chain;
  ImGui::TextDisabled("The options of `mrsim-scenario new`.");
  ImGui::InputText("name", &c.name);
  ImGui::InputInt("modules", &c.modules);
  ImGui::Combo("pattern", &template_pattern_, "pitch\0yaw\0pitch-yaw\0");
  ImGui::Combo("sensor modules", &template_sensors_,
               "none\0all (front, between, back)\0between modules\0");
  ImGui::Checkbox("force plate under each sensor module", &c.force_sensors);
  ImGui::Checkbox("distance sensor at the front", &c.front_distance_sensor);
  ImGui::InputDouble("module mass [kg]", &c.module_mass, 0, 0, "%.4g");
  double edge = c.frame_size.x();
  if (ImGui::InputDouble("frame edge [m]", &edge, 0, 0, "%.4g")) {
    c.frame_size.setConstant(edge);
  }
  ImGui::InputDouble("Kp [1/s]", &c.kp, 0, 0, "%.4g");
  ImGui::InputDouble("max_vel [rad/s]", &c.max_vel, 0, 0, "%.4g");
  ImGui::InputDouble("joint limit [rad]", &c.joint_limit, 0, 0, "%.4g");
  ImGui::InputText("material", &c.material);
  ImGui::InputText("ground material", &template_.ground_material);
  ImGui::InputDouble("friction (<0: none)", &template_.friction, 0, 0, "%.4g");
  if (!message_.empty()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(message_is_error_
                           ? ImVec4(1, 0.4f, 0.4f, 1)
                           : ImGui::GetStyleColorVec4(ImGuiCol_Text),
                       "%s", message_.c_str());
    ImGui::PopTextWrapPos();
  }
  if (Button("Create", 120)) {
    c.pattern = static_cast<ChainPattern>(template_pattern_);
    c.sensor_after =
        SensorsAfter(static_cast<SensorPlacement>(template_sensors_),
                     std::max(1, c.modules));
    try {
      Design fresh;
      fresh.ApplyTemplate(template_);
      design_ = std::move(fresh);
      built_revision_ = -1;
      message_.clear();
      show_template_ = false;
      ImGui::CloseCurrentPopup();
      preview_->Reframe();
    } catch (const std::exception& e) {
      Refuse(e.what());
    }
  }
  ImGui::SameLine();
  if (Button("Cancel", 120)) {
    show_template_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void StudioApp::DrawHelp() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x / 2 - 210, 60));
  ImGui::SetNextWindowSize(ImVec2(420, 0));
  ImGui::SetNextWindowBgAlpha(0.92f);
  ImGui::Begin("Help", &show_help_,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoSavedSettings);
  const char* rows[][2] = {
      {"left drag", "orbit the view"},
      {"right drag, shift+left drag", "pan"},
      {"wheel", "zoom"},
      {"click a part", "select it (inspector)"},
      {"F", "frame the whole scene"},
      {"Delete", "remove the selected part"},
      {"Ctrl+Z / Ctrl+Y", "undo / redo"},
      {"Ctrl+N / Ctrl+O", "new / open"},
      {"Ctrl+S / Ctrl+Shift+S", "save / save as"},
      {"Ctrl+Q", "quit (asks when unsaved or running)"},
      {"F5", "Run panel / inspector"},
      {"Up / Down", "while running: forward / backward"},
      {"Left / Right", "while running: turn"},
      {"Space", "while running: stop the robot"},
      {"F1", "this help"},
  };
  for (const auto& r : rows) {
    ImGui::TextUnformatted(r[0]);
    ImGui::SameLine(200);
    ImGui::TextDisabled("%s", r[1]);
  }
  ImGui::End();
}

}  // namespace mrsim::studio
