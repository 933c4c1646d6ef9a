#include "studio/ui/run/controller_panel.h"

#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/input_limits.h"
#include "gait_controller/gait_presets.h"
#include "lua_controller/lua_templates.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {
namespace {

constexpr int kGait = static_cast<int>(ControllerKind::kGait);
constexpr int kLua = static_cast<int>(ControllerKind::kLua);
constexpr int kExternal = static_cast<int>(ControllerKind::kExternal);
constexpr const char* kScriptName = "controller.lua";

}  // namespace

ControllerPanel::ControllerPanel() {
  if (!LuaTemplates().empty()) source_ = LuaTemplates().front().source;
  for (size_t i = 0; i < GaitPresets().size(); ++i) {
    if (GaitPresets()[i].name == "forward") gait_ = static_cast<int>(i);
  }
}

std::string ControllerPanel::gait() const {
  const auto& presets = GaitPresets();
  if (gait_ == kDesignGait && !design_gait_.empty()) return design_gait_;
  if (gait_ < 0 || gait_ >= static_cast<int>(presets.size())) return "forward";
  return presets[gait_].name;
}

void ControllerPanel::Set(ControllerKind kind, const std::string& gait,
                          const std::string& lua_source,
                          const std::string& external_name) {
  kind_ = static_cast<int>(kind);
  // A gait that is no preset stays what the design says (and is offered
  // in the list), so saving the design again keeps it.
  design_gait_.clear();
  gait_ = kDesignGait;
  for (size_t i = 0; i < GaitPresets().size(); ++i) {
    if (GaitPresets()[i].name == gait) gait_ = static_cast<int>(i);
  }
  if (gait_ == kDesignGait) design_gait_ = gait;
  if (!lua_source.empty()) source_ = lua_source;
  if (!external_name.empty()) external_ = external_name;
}

void ControllerPanel::CheckNow() {
  if (checked_ == source_ && (error_ || !checked_.empty())) return;
  // Loading runs the top level under the sandbox's limits: cheap, and
  // only when the text changed.
  error_ = LuaScript::Check(source_, kScriptName);
  checked_ = source_;
}

void ControllerPanel::Draw(LayoutRecorder* layout) {
  ImGui::TextUnformatted("Controller");
  ImGui::SameLine();
  ImGui::RadioButton("gait", &kind_, kGait);
  RecordItem(layout, "controller gait");
  ImGui::SameLine();
  ImGui::RadioButton("Lua script", &kind_, kLua);
  RecordItem(layout, "controller lua");
  ImGui::SameLine();
  ImGui::RadioButton("external", &kind_, kExternal);
  RecordItem(layout, "controller external");
  if (layout != nullptr && layout->enabled()) {
    layout->State("controller", ToString(kind()));
  }
  if (kind_ == kGait) {
    const auto& presets = GaitPresets();
    const std::string current = gait();
    ImGui::SetNextItemWidth(160);
    if (ImGui::BeginCombo("starting gait", current.c_str())) {
      if (!design_gait_.empty() &&
          ImGui::Selectable(design_gait_.c_str(), gait_ == kDesignGait)) {
        gait_ = kDesignGait;
      }
      for (size_t i = 0; i < presets.size(); ++i) {
        if (ImGui::Selectable(presets[i].name.c_str(),
                              static_cast<int>(i) == gait_)) {
          gait_ = static_cast<int>(i);
        }
      }
      ImGui::EndCombo();
    }
    return;
  }
  if (kind_ == kExternal) {
    ImGui::SetNextItemWidth(160);
    ImGui::InputText("controller name", &external_);
    RecordItem(layout, "external name");
    ImGui::PushTextWrapPos(0);
    ImGui::TextDisabled(
        "Run starts the simulator in lockstep: it waits at every step for "
        "joint commands whose sender is '%s'. Start your program with that "
        "name, e.g. examples/python/controller.py --name %s (Python: "
        "mrsim.Node(name=...); C++: joint_command_t on "
        "<prefix>_COMMAND_<robot>).",
        external_.c_str(), external_.c_str());
    ImGui::PopTextWrapPos();
    if (!ValidControllerName(external_)) {
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1),
                         "a name is 1-64 letters, digits, - _ or .");
    }
    return;
  }
  // Lua: templates, the editor, the check.
  const auto& templates = LuaTemplates();
  if (!templates.empty()) {
    template_ =
        std::clamp(template_, 0, static_cast<int>(templates.size()) - 1);
    ImGui::SetNextItemWidth(120);
    if (ImGui::BeginCombo("##template", templates[template_].name.c_str())) {
      for (size_t i = 0; i < templates.size(); ++i) {
        if (ImGui::Selectable(templates[i].name.c_str(),
                              static_cast<int>(i) == template_)) {
          template_ = static_cast<int>(i);
        }
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (RecordedButton(layout, "Use template")) {
      source_ = templates[template_].source;
    }
    ImGui::SameLine();
  }
  if (RecordedButton(layout, "Clear script")) source_.clear();
  ImGui::InputTextMultiline("##lua", &source_, ImVec2(-1, 200),
                            ImGuiInputTextFlags_AllowTabInput);
  RecordItem(layout, "lua editor");
  if (source_.size() > kMaxLuaScriptBytes) {
    source_.resize(kMaxLuaScriptBytes);
  }
  CheckNow();
  int lines = 1;
  for (char c : source_) lines += c == '\n';
  if (layout != nullptr && layout->enabled()) {
    layout->State("lua lines", std::to_string(lines));
    layout->State("lua error line",
                  error_ ? std::to_string(error_->line()) : "0");
    layout->State("lua error", error_ ? error_->what() : "");
  }
  ImGui::PushTextWrapPos(0);
  if (error_) {
    if (error_->line() > 0) {
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "line %d: %s",
                         error_->line(), error_->what());
    } else {
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_->what());
    }
  } else {
    ImGui::TextColored(ImVec4(0.5f, 0.9f, 0.5f, 1),
                       "script OK: step(t, state) returns one angle per "
                       "joint (docs/gait.md)");
  }
  ImGui::PopTextWrapPos();
}

std::string ControllerPanel::ScriptPathFor(const std::string& design_path) {
  std::filesystem::path p(design_path);
  p.replace_extension(".controller.lua");
  return p.string();
}

void ControllerPanel::Fill(RunOptions* o,
                           const std::string& design_path) const {
  switch (kind_) {
    case kGait:
      o->controller = ControllerKind::kGait;
      o->gait = gait();
      return;
    case kExternal:
      o->controller = ControllerKind::kExternal;
      o->external_name = external_;
      return;
    default:
      break;
  }
  if (auto error = LuaScript::Check(source_, kScriptName)) {
    throw std::invalid_argument(
        error->line() > 0
            ? fmt::format("the Lua script has an error at line {}: {}",
                          error->line(), error->what())
            : fmt::format("the Lua script: {}", error->what()));
  }
  const std::string path = ScriptPathFor(design_path);
  WriteFileAtomically(path, source_);
  o->controller = ControllerKind::kLua;
  o->lua_script = path;
}

}  // namespace mrsim::studio
