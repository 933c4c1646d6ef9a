#include "studio/ui/panels/status_bar.h"

#include <imgui.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void StatusBar::DrawViewMenu(StudioContext& studio) {
  if (!ImGui::BeginPopup("view menu")) return;
  PanelSettings& p = studio.panels;
  ImGui::MenuItem("Design panel", "Tab", &p.show_left);
  studio.Record("view Design panel");
  ImGui::MenuItem(studio.show_run ? "Run panel" : "Inspector", "Shift+Tab",
                  &p.show_right);
  studio.Record("view right panel");
  if (ImGui::MenuItem("3-D view only", "F11", !p.show_left && !p.show_right)) {
    studio.ToggleFullView();
  }
  studio.Record("view 3-D only");
  ImGui::Separator();
  if (ImGui::MenuItem(studio.video.recording() ? "Stop video" : "Record video",
                      "Ctrl+R")) {
    studio.ToggleVideo();
  }
  studio.Record("view video");
  if (!studio.video.videos().empty()) {
    ImGui::TextDisabled("Videos (3-D view, MP4)");
    for (const RecordedVideo& v : studio.video.videos()) {
      ImGui::Text("%s  %s",
                  std::filesystem::path(v.path).filename().string().c_str(),
                  DescribeVideo(v).c_str());
      if (ImGui::IsItemHovered()) WrappedTooltip(v.path);
    }
  }
  ImGui::Separator();
  ImGui::TextDisabled("Drag a panel's inner edge to resize it");
  ImGui::EndPopup();
}

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
  if (studio.Button("View")) ImGui::OpenPopup("view menu");
  DrawViewMenu(studio);
  if (studio.video.recording()) {
    ImGui::SameLine();
    ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.7f, 0.1f, 0.1f, 1));
    char label[48];
    std::snprintf(label, sizeof(label), "Stop video %.0f s###Stop video",
                  studio.video.seconds());
    const bool stop = ImGui::Button(label);
    studio.Record("Stop video");
    ImGui::PopStyleColor();
    if (stop) studio.ToggleVideo();
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
    // The longest hint that fits beside the file name and buttons (never
    // cut mid-word); all of it on hover.
    static const char* const kHints[] = {
        "drag: orbit  right-drag: pan  wheel: zoom  F: frame",
        "drag: orbit  right-drag: pan  wheel: zoom", "drag: orbit  wheel: zoom",
        "hover: controls"};
    const float room = ImGui::GetContentRegionAvail().x;
    const char* hint = kHints[3];
    for (const char* h : kHints) {
      if (ImGui::CalcTextSize(h).x <= room) {
        hint = h;
        break;
      }
    }
    ImGui::TextDisabled("%s", hint);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "drag: orbit, right-drag (or shift+drag): pan, wheel: zoom\n"
          "F: frame the whole scene, click: select a part\nF1: help");
    }
  }
  ImGui::End();
}

}  // namespace mrsim::studio
