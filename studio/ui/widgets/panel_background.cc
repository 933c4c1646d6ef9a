#include "studio/ui/widgets/panel_background.h"

#include <cmath>

namespace mrsim::studio {
namespace {

// Under the panels before they lost their background: what the window was
// cleared to.
constexpr float kBase[3] = {0.12f, 0.13f, 0.15f};

}  // namespace

ImVec4 PanelClearColour() {
  // As the 8-bit framebuffer had it: ImGui's colour as its vertices carry
  // it, the base as the clear stored it, blended (SRC_ALPHA,
  // ONE_MINUS_SRC_ALPHA).
  const ImVec4 bg =
      ImGui::ColorConvertU32ToFloat4(ImGui::GetColorU32(ImGuiCol_WindowBg));
  auto stored = [](float c) { return std::round(c * 255) / 255; };
  const float a = bg.w;
  return ImVec4(a * bg.x + (1 - a) * stored(kBase[0]),
                a * bg.y + (1 - a) * stored(kBase[1]),
                a * bg.z + (1 - a) * stored(kBase[2]), 1.0f);
}

void SkipPanelBackground() { ImGui::SetNextWindowBgAlpha(0.0f); }

}  // namespace mrsim::studio
