// The Run panel's Recording section: mrsim-log into a new folder.
// Part of LivePanel (live_panel.h), one file per section.
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawRecording() {
  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##recdir", &record_dir_);
  ImGui::SameLine();
  if (!runner_.recording()) {
    if (RecordedButton(layout_, "Record")) {
      try {
        runner_.StartRecording(
            NewRecordingFolder(record_dir_, std::time(nullptr)));
      } catch (const std::exception& e) {
        message_ = e.what();
        message_is_note_ = false;
      }
    }
  } else if (RecordedButton(layout_, "Stop recording")) {
    runner_.StopRecording();
  }
  if (!runner_.record_dir().empty()) {
    // In full: a student looks for it in a file manager.
    std::error_code ec;
    const std::string folder =
        std::filesystem::absolute(runner_.record_dir(), ec).string();
    ImGui::TextWrapped("%s %s",
                       runner_.recording() ? "recording to" : "recorded in",
                       folder.c_str());
  }
  for (const RecordedFile& f : runner_.RecordedFiles()) {
    ImGui::Text("  %s  %lld rows",
                std::filesystem::path(f.path).filename().string().c_str(),
                static_cast<long long>(f.rows));
  }
}

}  // namespace mrsim::studio
