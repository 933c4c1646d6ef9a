// The Run panel's Steering section: the followed robot, motion buttons,
// gait files and the seven gait parameters.
// Part of LivePanel (live_panel.h), one file per section.
#include <iterator>

#include "gait_controller/gait_file.h"
#include "gait_controller/process/gait_parameters_message.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawSteering() {
  std::vector<std::string> names;
  if (link_) {
    for (const LiveRobot* r : session_->robots()) names.push_back(r->name);
  }
  if (names.empty()) {
    ImGui::TextDisabled("no robot heard yet");
    return;
  }
  if (ImGui::BeginCombo("robot", followed_.c_str())) {
    for (const std::string& n : names) {
      if (ImGui::Selectable(n.c_str(), n == followed_)) followed_ = n;
    }
    ImGui::EndCombo();
  }
  const LiveRobot* robot = session_->robot(followed_);
  if (robot != nullptr && robot->gait) {
    ImGui::Text("gait %s (%s %.2f)%s", robot->gait->gait.c_str(),
                robot->gait->motion.c_str(), robot->gait->strength,
                robot->silent ? "  silent" : "");
  }
  // Offered only where a controller answers (LiveSession::SteeringOf).
  const Steering steering = FollowedSteering();
  const bool off = steering.state == Steering::State::kUnanswered;
  if (!steering.why.empty()) {
    if (off) {
      ImGui::TextWrapped("%s", steering.why.c_str());
    } else {
      ImGui::PushTextWrapPos(0);
      ImGui::TextDisabled("%s", steering.why.c_str());
      ImGui::PopTextWrapPos();
    }
  }
  ImGui::BeginDisabled(off);
  ImGui::SetNextItemWidth(150);
  ImGui::SliderFloat("strength", &strength_, -1.0f, 1.0f, "%.2f");
  const char* const motions[] = {
      "forward",       "backward",       "turn-left", "turn-right",
      "sidewind-left", "sidewind-right", "roll",      "stop"};
  // Four to a row, as wide as the panel allows (fixed widths ran past its
  // edge beside the scroll bar).
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const float button =
      std::floor((ImGui::GetContentRegionAvail().x - 3 * spacing) / 4);
  // Narrow padding: "sidewind-right" is the widest name and must fit.
  ImGui::PushStyleVar(ImGuiStyleVar_FramePadding,
                      ImVec2(1, ImGui::GetStyle().FramePadding.y));
  for (int i = 0; i < IM_ARRAYSIZE(motions); ++i) {
    if (i % 4 != 0) ImGui::SameLine();
    if (RecordedButton(layout_, motions[i], button)) {
      Send([&](StudioOutbox* out) {
        session_->Steer(followed_, motions[i], strength_, WallClock::now(),
                        out);
      });
    }
  }
  ImGui::PopStyleVar();
  ImGui::SetNextItemWidth(-170);
  ImGui::InputText("##gaitfile", &gait_file_);
  ImGui::SameLine();
  if (RecordedButton(layout_, "Load gait")) {
    // A preset name or a gait file mrsim-gait can read (on its machine).
    Send([&](StudioOutbox* out) {
      session_->SetGait(followed_, gait_file_, WallClock::now(), out);
    });
  }
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (RecordedButton(layout_, "Save gait")) {
    try {
      if (robot == nullptr || !robot->gait) {
        throw std::runtime_error("no gait heard yet");
      }
      if (robot->gait->kind == "lua") {  // mrsim-lua's status
        throw std::runtime_error(
            "robot '" + followed_ +
            "' is driven by a Lua script: it has no gait to save");
      }
      Gait gait;
      gait.name = std::filesystem::path(gait_file_).stem().string();
      gait.kind = ParseGaitKind(robot->gait->kind).value_or(GaitKind::kLinear);
      gait.parameters = GaitParametersFromMessage(robot->gait->parameters);
      WriteGaitFile(gait, gait_file_);
      message_ = "wrote " + gait_file_;
      message_is_note_ = true;
    } catch (const std::exception& e) {
      message_ = e.what();
      message_is_note_ = false;
    }
  }
  ImGui::BeginDisabled(off);
  if (ImGui::TreeNode("gait parameters")) {
    const auto& parameter_names = GaitParameterNames();
    bool changed = false;
    for (int i = 0; i < GaitParameters::kVectorSize; ++i) {
      ImGui::SetNextItemWidth(150);
      // The period's unit beside its name, as the user types seconds.
      const std::string label =
          std::string(parameter_names[i]) +
          (parameter_names[i] == std::string("T") ? " (s)" : "");
      changed |= ImGui::DragFloat(label.c_str(), &parameters_[i], 0.01f);
    }
    if (changed) {
      // Kept for Save and the next Run: the design runs as it was left.
      Gait tuned;
      tuned.name = "tuned";
      if (robot != nullptr && robot->gait) {
        tuned.kind =
            ParseGaitKind(robot->gait->kind).value_or(GaitKind::kLinear);
      }
      tuned.parameters = GaitParameters::FromVector(
          std::vector<double>(std::begin(parameters_), std::end(parameters_)));
      tuned_gait_ = tuned;
      Send([&](StudioOutbox* out) {
        session_->SetGaitParameters(
            followed_,
            std::vector<double>(std::begin(parameters_), std::end(parameters_)),
            WallClock::now(), out);
      });
    }
    ImGui::TreePop();
  }
  ImGui::EndDisabled();
}

}  // namespace mrsim::studio
