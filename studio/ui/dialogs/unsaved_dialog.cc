#include "studio/ui/dialogs/unsaved_dialog.h"

#include <imgui.h>

#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void UnsavedDialog::Draw(StudioContext& studio) {
  if (studio.ask_unsaved) {
    ImGui::OpenPopup("Unsaved changes");
  }
  if (BeginFixedModal("Unsaved changes", 360, 90,
                      ImGui::GetIO().DisplaySize.y / 2 - 45)) {
    // Reported (for tests) once it takes clicks: not on its first frame.
    shown_ = !ImGui::IsWindowAppearing();
    ImGui::TextWrapped("The design has unsaved changes. Save them first?");
    const bool save = ImGui::Button("Save", ImVec2(100, 0));
    studio.Record("unsaved Save");
    if (save) {
      studio.ask_unsaved = false;
      ImGui::CloseCurrentPopup();
      if (studio.design.path().empty()) {
        studio.SaveFile();  // Save As first; the pending action follows it
      } else {
        studio.SaveFile();
        if (!studio.design.dirty()) studio.RunPending();
      }
    }
    ImGui::SameLine();
    const bool discard = ImGui::Button("Discard", ImVec2(100, 0));
    studio.Record("unsaved Discard");
    if (discard) {
      studio.ask_unsaved = false;
      ImGui::CloseCurrentPopup();
      if (studio.pending == Pending::kOpen && !studio.pending_path.empty()) {
        studio.pending = Pending::kNone;
        studio.OpenFile(studio.pending_path);
        studio.pending_path.clear();
      } else {
        studio.RunPending();
      }
    }
    ImGui::SameLine();
    const bool cancel = ImGui::Button("Cancel", ImVec2(100, 0));
    studio.Record("unsaved Cancel");
    if (cancel) {
      studio.ask_unsaved = false;
      studio.pending = Pending::kNone;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

}  // namespace mrsim::studio
