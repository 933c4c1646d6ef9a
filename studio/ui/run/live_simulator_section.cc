// The Run panel's Simulator section: status, pause, step, reset, speed,
// checkpoints.
// Part of LivePanel (live_panel.h), one file per section.
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawControls() {
  // Detached or stopped: the last run's figures would read as live ones.
  const std::optional<sim_status_t> none;
  const auto& status = link_ ? session_->sim_status() : none;
  if (status) {
    ImGui::Text("sim %.2f s  x%.2f  %s%s", status->sim_time,
                status->real_time_factor, status->clock.c_str(),
                status->mode == sim_status_t::PAUSED ? "  paused" : "");
    if (!status->waiting_for.empty()) {
      ImGui::Text("lockstep waits for %s", status->waiting_for.c_str());
    }
    ImGui::Text("applied %lld  rejected %lld  malformed %lld",
                static_cast<long long>(status->commands_applied),
                static_cast<long long>(status->commands_rejected),
                static_cast<long long>(status->messages_malformed));
  } else {
    ImGui::TextDisabled(link_ ? "waiting for the simulator..."
                              : "not connected");
  }
  // What this window itself dropped: bytes that were not the channel's
  // type (someone else's traffic, or a hostile host on the group).
  if (link_ && session_->malformed() + session_->foreign() > 0) {
    ImGui::TextDisabled("studio dropped %lld malformed, %lld foreign",
                        static_cast<long long>(session_->malformed()),
                        static_cast<long long>(session_->foreign()));
  }
  const bool paused = status && status->mode == sim_status_t::PAUSED;
  if (RecordedButton(layout_, paused ? "Play" : "Pause")) {
    Send([&](StudioOutbox* out) {
      paused ? session_->Resume(WallClock::now(), out)
             : session_->Pause(WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  if (RecordedButton(layout_, "Step")) {
    Send([&](StudioOutbox* out) {
      session_->Step(step_periods_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputInt("periods", &step_periods_);
  ImGui::SameLine();
  if (RecordedButton(layout_, "Reset")) {
    Send([&](StudioOutbox* out) { session_->Reset(WallClock::now(), out); });
  }
  ImGui::SetNextItemWidth(120);
  static const double kSlowest = 0.1, kFastest = 4.0;
  if (ImGui::SliderScalar("real-time factor", ImGuiDataType_Double, &speed_,
                          &kSlowest, &kFastest, "%.2f",
                          ImGuiSliderFlags_Logarithmic) &&
      link_) {
    Send([&](StudioOutbox* out) {
      session_->SetSpeed(speed_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  ImGui::Checkbox("camera follows", &camera_follows_);
  RecordItem(layout_, "camera follows");
  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##checkpoint", &checkpoint_);
  ImGui::SameLine();
  if (RecordedButton(layout_, "Save##ckpt")) {
    Send([&](StudioOutbox* out) {
      session_->SaveCheckpoint(checkpoint_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  if (RecordedButton(layout_, "Load##ckpt")) {
    Send([&](StudioOutbox* out) {
      session_->LoadCheckpoint(checkpoint_, WallClock::now(), out);
    });
  }
  const auto& requests = session_->requests();
  if (!requests.empty()) {
    const LiveRequest& r = requests.back();
    ImGui::Text("%s: %s%s%s", r.what.c_str(), RequestText(r.state),
                r.error.empty() ? "" : " - ", r.error.c_str());
  }
}

}  // namespace mrsim::studio
