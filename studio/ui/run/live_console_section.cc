// The Run panel's Console section: the children's output.
// Part of LivePanel (live_panel.h), one file per section.
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawConsole(float height) {
  // Long lines scroll sideways rather than being cut off.
  ImGui::BeginChild("console", ImVec2(0, height), true,
                    ImGuiWindowFlags_HorizontalScrollbar);
  for (const std::string& line : runner_.console()) {
    ImGui::TextUnformatted(line.c_str());
  }
  for (const std::string& line : optimise_.console()) {
    ImGui::TextUnformatted(line.c_str());
  }
  if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) {
    ImGui::SetScrollHereY(1.0f);
  }
  ImGui::EndChild();
}

}  // namespace mrsim::studio
