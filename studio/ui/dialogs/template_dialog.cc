#include "studio/ui/dialogs/template_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <utility>

#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

TemplateDialog::TemplateDialog() {
  template_.chain.modules = 5;
  template_.chain.pattern = ChainPattern::kPitchYaw;
}

void TemplateDialog::Draw(StudioContext& studio) {
  ImGui::OpenPopup("New robot from template");
  if (!BeginFixedModal("New robot from template", 460, 480,
                       ImGui::GetIO().DisplaySize.y / 2 - 240)) {
    return;
  }
  ChainOptions& c = template_.chain;
  ImGui::TextDisabled("The options of `mrsim-scenario new`.");
  ImGui::InputText("name", &c.name);
  ImGui::InputInt("modules", &c.modules);
  ImGui::Combo("pattern", &template_pattern_, "pitch\0yaw\0pitch-yaw\0");
  ImGui::Combo("sensor modules", &template_sensors_,
               "none\0all (front, between, back)\0between modules\0");
  ImGui::Checkbox("force plate under each sensor module", &c.force_sensors);
  ImGui::Checkbox("distance sensor at the front", &c.front_distance_sensor);
  ImGui::InputDouble("module mass [kg]", &c.module_mass, 0, 0, "%.4g");
  double edge = c.frame_size.x();
  if (ImGui::InputDouble("frame edge [m]", &edge, 0, 0, "%.4g")) {
    c.frame_size.setConstant(edge);
  }
  ImGui::InputDouble("Kp [1/s]", &c.kp, 0, 0, "%.4g");
  ImGui::InputDouble("max_vel [rad/s]", &c.max_vel, 0, 0, "%.4g");
  ImGui::InputDouble("joint limit [rad]", &c.joint_limit, 0, 0, "%.4g");
  ImGui::InputText("material", &c.material);
  ImGui::InputText("ground material", &template_.ground_material);
  ImGui::InputDouble("friction (<0: none)", &template_.friction, 0, 0, "%.4g");
  if (!studio.message.empty()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(studio.message_is_error
                           ? ImVec4(1, 0.4f, 0.4f, 1)
                           : ImGui::GetStyleColorVec4(ImGuiCol_Text),
                       "%s", studio.message.c_str());
    ImGui::PopTextWrapPos();
  }
  if (studio.Button("Create", 120)) {
    c.pattern = static_cast<ChainPattern>(template_pattern_);
    c.sensor_after =
        SensorsAfter(static_cast<SensorPlacement>(template_sensors_),
                     std::max(1, c.modules));
    try {
      Design fresh;
      fresh.ApplyTemplate(template_);
      studio.design = std::move(fresh);
      studio.built_revision = -1;
      studio.message.clear();
      studio.show_template = false;
      ImGui::CloseCurrentPopup();
      studio.preview->Reframe();
    } catch (const std::exception& e) {
      studio.Refuse(e.what());
    }
  }
  ImGui::SameLine();
  if (studio.Button("Cancel", 120)) {
    studio.show_template = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

}  // namespace mrsim::studio
