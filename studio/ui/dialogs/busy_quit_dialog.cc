#include "studio/ui/dialogs/busy_quit_dialog.h"

#include <imgui.h>

#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void BusyQuitDialog::Draw(StudioContext& studio) {
  if (studio.ask_busy_quit.empty()) return;
  ImGui::OpenPopup("Quit while running?");
  if (!BeginFixedModal("Quit while running?", 420, 0,
                       ImGui::GetIO().DisplaySize.y / 2 - 60)) {
    return;
  }
  shown_ = !ImGui::IsWindowAppearing();
  ImGui::TextWrapped("%s", studio.ask_busy_quit.c_str());
  const bool quit = ImGui::Button("Stop and quit", ImVec2(190, 0));
  studio.Record("busy Quit");
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel", ImVec2(190, 0));
  studio.Record("busy Cancel");
  if (quit || cancel) {
    studio.ask_busy_quit.clear();
    shown_ = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  if (quit) studio.Guard(Pending::kQuit);  // unsaved changes are asked next
}

}  // namespace mrsim::studio
