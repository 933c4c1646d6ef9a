#include "studio/ui/status_bar.h"

#include <imgui.h>

#include <filesystem>
#include <string>

#include "studio/ui/widgets.h"

namespace mrsim::studio {

void StatusBar::Draw(StudioContext& studio, const PanelRect& rect) {
  const float x = rect.x, y = rect.y, w = rect.w;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, rect.h));
  ImGui::Begin(
      "status", nullptr,
      kPanelFlags | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoScrollbar);
  const std::string name =
      studio.design.path().empty()
          ? std::string("untitled")
          : std::filesystem::path(studio.design.path()).filename().string();
  ImGui::Text("%s%s", name.c_str(), studio.design.dirty() ? " *" : "");
  ImGui::SameLine();
  if (studio.Button(studio.show_run ? "Inspector (F5)" : "Run panel (F5)")) {
    studio.show_run = !studio.show_run;
  }
  ImGui::SameLine();
  if (!studio.build_error.empty()) {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "preview: %s",
                       studio.build_error.c_str());
    // One line is often too short for an error naming a file and field.
    if (ImGui::IsItemHovered()) WrappedTooltip(studio.build_error);
  } else if (!studio.message.empty()) {
    if (studio.message_is_error) {
      ImGui::TextColored(ImVec4(1, 0.75f, 0.3f, 1), "%s",
                         studio.message.c_str());
    } else {
      ImGui::TextUnformatted(studio.message.c_str());
    }
    if (ImGui::IsItemHovered()) WrappedTooltip(studio.message);
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

}  // namespace mrsim::studio
