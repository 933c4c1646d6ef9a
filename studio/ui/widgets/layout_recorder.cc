#include "studio/ui/widgets/layout_recorder.h"

#include <cstdio>
#include <fstream>

namespace mrsim::studio {

void LayoutRecorder::Widget(const std::string& name, float x, float y, float w,
                            float h) {
  if (!enabled()) return;
  char rect[96];
  std::snprintf(rect, sizeof(rect), "%.0f %.0f %.0f %.0f", x, y, w, h);
  lines_["widget " + name] = rect;
}

void LayoutRecorder::State(const std::string& key, const std::string& value) {
  if (enabled()) lines_[key] = value;
}

void LayoutRecorder::EndFrame() {
  if (!enabled()) return;
  std::string text;
  for (const auto& [key, value] : lines_) text += key + "\t" + value + "\n";
  text += "end\n";
  if (text == written_) return;
  const std::string tmp = path_ + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out) return;  // a test helper: never stop the studio for it
  }
  if (std::rename(tmp.c_str(), path_.c_str()) == 0) written_ = text;
}

}  // namespace mrsim::studio
