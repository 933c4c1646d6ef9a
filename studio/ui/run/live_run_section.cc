// The Run panel's first section: run the design (saved first) or attach to
// a simulation; stop or detach.
// Part of LivePanel (live_panel.h), one file per section.
#include <algorithm>

#include "gait_controller/gait_file.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/live/saved_run.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawRun(const LiveDesign& design) {
  ImGui::TextUnformatted("Run this design");
  ImGui::SetNextItemWidth(110);
  EnumCombo("clock", &clock_, ClockModes());
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputDouble("Hz", &rate_, 0, 0, "%g");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputDouble("speed", &speed_, 0, 0, "%g");
  controller_.Draw(layout_);
  if (tuned_gait_ && controller_.kind() == ControllerKind::kGait) {
    // What Run starts instead of the starting gait above, and why.
    ImGui::TextDisabled("starts with the gait tuned below (saved with it)");
    RecordItem(layout_, "tuned gait note");
    ImGui::SameLine();
    if (RecordedButton(layout_, "Forget tuned gait")) tuned_gait_.reset();
  }
  if (!runner_.running()) {
    // mrsim-sim runs the file: what is on screen is saved first.
    const bool saved = !design.path.empty() && !design.dirty;
    // REQ-1.2.8: parts that overlap at the start are pushed apart by the
    // first step, and the run is not the design; mrsim-sim refuses them
    // unless told, and the button says why beside it.
    const bool refused = !design.overlaps.empty() && !allow_overlap_;
    ImGui::BeginDisabled(refused);
    const bool pressed =
        RecordedButton(layout_, saved ? "Run" : "Save and Run");
    ImGui::EndDisabled();
    if (pressed) {
      const std::string path =
          saved ? design.path : (design.save ? design.save() : "");
      if (path.empty()) {
        message_ =
            "the design is not saved yet: choose where to save it, then "
            "press Run";
        message_is_note_ = false;
      } else {
        try {
          RunOptions o = FormRun();
          o.scenario_path = path;
          o.robots = design.robots;
          controller_.Fill(&o, path);
          // Beside the design, as the Lua script is.
          UseTunedGait(FormRunSettings(), "the tuned gait",
                       std::filesystem::path(path)
                           .replace_extension(".tuned.gait.xml")
                           .string(),
                       &o);
          o.allow_overlap = !design.overlaps.empty() && allow_overlap_;
          runner_.Start(o);
          Connect(url_, prefix_);
          run_controller_ = o.controller;
          EndReplay();
          running_ = ReadScenarioFile(path);
          ++replay_revision_;
          message_.clear();
        } catch (const std::exception& e) {
          message_ = e.what();
          message_is_note_ = false;
        }
      }
    }
  } else if (RecordedButton(layout_, "Stop")) {
    // Back to the design: the view, the camera and the simulator section
    // leave the stopped run (its last pose and counters would look live).
    runner_.Stop();
    EndReplay();
    Disconnect();
  }
  ImGui::SameLine();
  if (!link_) {
    if (RecordedButton(layout_, "Attach")) {
      try {
        Connect(url_, prefix_);
      } catch (const std::exception& e) {
        message_ = e.what();
        message_is_note_ = false;
      }
    }
  } else if (RecordedButton(layout_, "Detach")) {
    Disconnect();
  }
  if (!runner_.running()) {
    DrawOverlapRefusal(design, !design.overlaps.empty() && !allow_overlap_);
  }
  // A run on this computer needs neither; attaching to a simulation or a
  // farm elsewhere does. Folded, so a first look is not an LCM URL.
  if (ImGui::TreeNode("network (LCM URL, prefix)")) {
    ImGui::SetNextItemWidth(-60);
    ImGui::InputText("URL", &url_);
    ImGui::SetNextItemWidth(-60);
    ImGui::InputText("prefix", &prefix_);
    ImGui::TreePop();
  }
}

void LivePanel::DrawOverlapRefusal(const LiveDesign& design, bool refused) {
  if (layout_ != nullptr) {
    layout_->State("run refused", refused ? design.overlaps.front() : "");
  }
  if (design.overlaps.empty()) return;
  if (refused) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
    ImGui::TextWrapped(
        "parts overlap at the start: %s%s", design.overlaps.front().c_str(),
        design.overlaps.size() > 1
            ? (" (and " + std::to_string(design.overlaps.size() - 1) +
               " more, in the Design panel)")
                  .c_str()
            : "");
    ImGui::PopStyleColor();
  }
  // The flag's words (--allow-overlap), so the studio and the command line
  // read alike.
  ImGui::Checkbox("allow overlap: run it anyway", &allow_overlap_);
  RecordItem(layout_, "checkbox allow overlap");
}

RunSettings LivePanel::FormRunSettings() const {
  RunOptions o = FormRun();
  o.controller = controller_.kind();
  o.gait = controller_.gait();
  o.external_name = controller_.external_name();
  return SettingsFromRunOptions(
      o, controller_.lua_source(),
      tuned_gait_ ? WriteGaitString(*tuned_gait_) : std::string());
}

void LivePanel::LoadRunSettings(const std::optional<RunSettings>& run) {
  const RunOptions o = RunOptionsFromSettings(run);
  const auto& clocks = ClockModes().entries();
  for (size_t i = 0; i < clocks.size(); ++i) {
    if (clocks[i].value == o.clock) clock_ = static_cast<int>(i);
  }
  rate_ = o.rate;
  speed_ = o.speed;
  controller_.Set(o.controller, o.gait, run ? run->lua_script : "",
                  o.external_name);
  tuned_gait_.reset();
  if (run && !run->tuned_gait.empty()) {
    try {
      tuned_gait_ = ReadGaitString(run->tuned_gait, "<run><tunedGait>");
      const std::vector<double> p = tuned_gait_->parameters.ToVector();
      for (int i = 0; i < GaitParameters::kVectorSize; ++i) {
        parameters_[i] = static_cast<float>(p[i]);
      }
    } catch (const GaitFileError& e) {
      message_ =
          std::string("the design's tuned gait is not used: ") + e.what();
      message_is_note_ = false;
    }
  }
}

RunOptions LivePanel::FormRun() const {
  RunOptions o;
  o.lcm_url = url_;
  o.prefix = prefix_;
  o.clock = ClockModes().entries().at(clock_).value;
  o.rate = rate_;
  o.speed = speed_;
  return o;
}

}  // namespace mrsim::studio
