#include "studio/design/panel_layout.h"

#include <algorithm>

namespace mrsim::studio {

PanelLayout LayOutPanels(int width, int height, const PanelSettings& s) {
  const float scale = std::clamp(s.ui_scale, 0.5f, 4.0f);
  const float w = static_cast<float>(std::max(width, 16));
  const float h = static_cast<float>(std::max(height, 16));
  float left = s.show_left ? s.left_width * scale : 0;
  float right = s.show_right ? s.right_width * scale : 0;
  // Panels fit beside the view's share; else both shrink in proportion.
  const float room = w * (1 - kMinViewShare);
  if (left + right > room) {
    const float minimum = kMinPanelWidth * scale;
    const float f = room / (left + right);
    if (left > 0) left = std::max(left * f, std::min(minimum, left));
    if (right > 0) right = std::max(right * f, std::min(minimum, right));
  }
  // A window too small even for the narrowest panels: the view keeps 16
  // px and the panels split what is left.
  const float most = std::max(0.0f, w - 16);
  if (left + right > most) {
    const float f = most / (left + right);
    left *= f;
    right *= f;
  }
  PanelLayout out;
  out.left = {0, 0, left, left > 0 ? h : 0};
  out.right = {w - right, 0, right, right > 0 ? h : 0};
  const float status = std::min(kStatusHeight * scale, h / 2);
  out.view = {left, status, w - left - right, h - status};
  out.status = {left, 0, w - left - right, status};
  return out;
}

float ChooseUiScale(float requested, float monitor_scale) {
  const float s = requested > 0 ? requested : monitor_scale;
  if (!(s > 0)) return 1;  // NaN or a monitor that reports nothing
  return std::clamp(s, 0.5f, 4.0f);
}

}  // namespace mrsim::studio
