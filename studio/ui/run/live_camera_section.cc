// The Run panel's Camera section: what a camera of the shown robots sees,
// live while a run goes (the design's pose otherwise), with a chooser when
// there are several. The picture is CameraFeed's (camera_feed.h); this
// draws it. Part of LivePanel (live_panel.h), one file per section.
#include <algorithm>
#include <cstdint>

#include "studio/ui/view/camera_feed.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawCamera(CameraFeed* feed, float width) {
  camera_shown_ = false;
  if (feed == nullptr || (feed->cameras().empty() && feed->error().empty())) {
    return;
  }
  if (!RecordedHeader(layout_, "Camera", true)) return;
  camera_shown_ = true;
  if (!feed->error().empty()) {
    ImGui::TextWrapped("%s", feed->error().c_str());
    return;
  }
  const std::vector<std::string> labels = feed->Labels();
  if (labels.size() > 1) {
    int chosen = feed->selected();
    ImGui::SetNextItemWidth(std::max(120.0f, width - 90));
    if (ImGui::Combo(
            "camera", &chosen,
            +[](void* data, int i, const char** text) {
              *text = static_cast<const std::vector<std::string>*>(data)
                          ->at(i)
                          .c_str();
              return true;
            },
            const_cast<std::vector<std::string>*>(&labels),
            static_cast<int>(labels.size()))) {
      feed->Select(chosen);
    }
    RecordItem(layout_, "camera chooser");
  } else {
    ImGui::TextUnformatted(labels.front().c_str());
  }
  const FeedPicture& p = feed->picture();
  if (feed->texture() == 0 || p.width <= 0 || p.height <= 0) {
    ImGui::TextDisabled("rendering ...");
    return;
  }
  // As wide as the panel (at most 2.5 times the picture) and at most
  // kMaxHeight high, so the sections under it stay in reach; same aspect.
  constexpr float kMaxHeight = 210;
  const float aspect = static_cast<float>(p.width) / p.height;
  const float w = std::min(
      {width - 24, 2.5f * static_cast<float>(p.width), kMaxHeight * aspect});
  const float h = w / aspect;
  ImGui::Image(
      reinterpret_cast<ImTextureID>(static_cast<intptr_t>(feed->texture())),
      ImVec2(w, h));
  RecordItem(layout_, "camera picture");
  if (p.seq >= 0) {
    ImGui::TextDisabled("t %.2f s, state %lld", p.sim_time,
                        static_cast<long long>(p.seq));
  } else {
    ImGui::TextDisabled("the design's pose (Run shows it live)");
  }
}

}  // namespace mrsim::studio
