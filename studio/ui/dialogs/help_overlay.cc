#include "studio/ui/dialogs/help_overlay.h"

#include <imgui.h>

namespace mrsim::studio {

void HelpOverlay::Draw(StudioContext& studio) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x / 2 - 210, 60));
  ImGui::SetNextWindowSize(ImVec2(420, 0));
  ImGui::SetNextWindowBgAlpha(0.92f);
  ImGui::Begin("Help", &studio.show_help,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoSavedSettings);
  const char* rows[][2] = {
      {"left drag", "orbit the view"},
      {"right drag, shift+left drag", "pan"},
      {"wheel", "zoom"},
      {"click a part", "select it (inspector)"},
      {"drag disc / ring knob", "move / turn the selected robot or object"},
      {"drag a row or a module", "reorder / insert (list or robot)"},
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
