#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void RecordItem(LayoutRecorder* layout, const std::string& name) {
  if (layout == nullptr || !layout->enabled()) return;
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  layout->Widget(name, a.x, a.y, b.x - a.x, b.y - a.y);
  if (ImGui::IsItemActive()) layout->State("active", name);
}

bool RecordedButton(LayoutRecorder* layout, const char* label, float width) {
  const bool pressed = ImGui::Button(label, ImVec2(width, 0));
  RecordItem(layout, label);
  return pressed;
}

bool RecordedHeader(LayoutRecorder* layout, const char* label,
                    bool open_at_start) {
  const bool open = ImGui::CollapsingHeader(
      label, open_at_start ? ImGuiTreeNodeFlags_DefaultOpen : 0);
  RecordItem(layout, std::string("header ") + label);
  return open;
}

bool BeginFixedModal(const char* title, float width, float height, float top) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x / 2 - width / 2, top));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  return ImGui::BeginPopupModal(
      title, nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
}

void WrappedTooltip(const std::string& text) {
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

}  // namespace mrsim::studio
