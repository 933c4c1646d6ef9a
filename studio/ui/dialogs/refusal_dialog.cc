#include "studio/ui/dialogs/refusal_dialog.h"

#include <imgui.h>

#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void RefusalDialog::Draw(StudioContext& studio) {
  if (studio.refused_action.empty()) return;
  ImGui::OpenPopup("Not done");
  if (!BeginFixedModal("Not done", 460, 0, ImGui::GetIO().DisplaySize.y / 3)) {
    return;
  }
  shown_ = !ImGui::IsWindowAppearing();
  ImGui::TextWrapped("Could not %s:", studio.refused_action.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.75f, 0.3f, 1));
  ImGui::TextWrapped("%s", studio.refused_why.c_str());
  ImGui::PopStyleColor();
  const bool ok = ImGui::Button("OK", ImVec2(120, 0)) ||
                  ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) ||
                  ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape));
  studio.Record("refused OK");
  if (ok) {
    studio.refused_action.clear();
    shown_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

}  // namespace mrsim::studio
