#include "gait_controller/process/controller_flags.h"

#include <stdexcept>

#include "gait_controller/process/joint_axes_spec.h"
#include "lcmtypes/runtime/usage_error.h"

namespace mrsim {

void ControllerFlags::AddFlags(CLI::App& app, NodeFields fields,
                               const Help& help) {
  fields_ = fields;
  app.add_option("--robot", robot, "Robot name (as in the scenario)")
      ->required();
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  AddAuthFlags(app, auth);
  app.add_option("--prefix", *fields.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--scenario", scenario_path,
                 "Scenario file mrsim-sim runs (gives " + help.scenario_gives +
                     "; without it or --axes, pitch-yaw is assumed)");
  app.add_option("--axes", axes_text,
                 "Joint axes instead of --scenario: pitch, yaw, pitch-yaw, "
                 "yaw-pitch or P/Y per joint");
  app.add_option("--rate", *fields.rate, help.rate)->capture_default_str();
  app.add_option("--name", name,
                 "Sender name (what mrsim-sim --controllers lists); default " +
                     kind + "-<robot>");
  app.add_flag("--exit-with-sim", *fields.exit_with_sim, help.exit_with_sim);
}

void ControllerFlags::Finish(const std::string& no_axes_warning) {
  sender = name.empty() ? kind + "-" + robot : name;
  try {
    if (!scenario_path.empty() && !axes_text.empty()) {
      throw std::invalid_argument("give --scenario or --axes, not both");
    }
    if (!scenario_path.empty()) {
      const auto axes = ScenarioJointAxes(scenario_path, robot);
      axes_for = [axes](int) { return axes; };
    } else {
      // Robot states do not say which joint is pitch or yaw: alternating
      // pitch-yaw is the common case (the case-study robot); say so.
      if (axes_text.empty()) warning = no_axes_warning;
      const JointAxesSpec spec(axes_text.empty() ? "pitch-yaw" : axes_text);
      axes_for = [spec](int n) { return spec.Expand(n); };
    }
    if (!(*fields_.rate >= 0)) {
      throw std::invalid_argument("--rate must be >= 0");
    }
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
}

}  // namespace mrsim
