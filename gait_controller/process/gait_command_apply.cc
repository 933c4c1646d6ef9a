#include "gait_controller/process/gait_command_apply.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "gait_controller/gait_file.h"
#include "gait_controller/process/gait_parameters_message.h"

namespace mrsim {

std::string ApplyGaitCommand(const gait_command_t& command,
                             GaitController* controller) {
  GaitController next = *controller;
  std::string what;
  if (!command.gait.empty()) {
    const Gait gait = ResolveGait(command.gait);
    next.SetGait(gait);
    what += fmt::format(" gait {} ({})", gait.name, ToString(gait.kind));
  }
  if (command.has_parameters) {
    const std::vector<double> values = GaitParameterValues(command.parameters);
    next.SetParameters(next.active_gait().parameters.WithVector(values));
    what += fmt::format(" parameters [{}]", fmt::join(values, ", "));
  }
  if (!command.motion.empty()) {
    const auto motion = ParseMotion(command.motion);
    if (!motion) {
      throw std::invalid_argument(fmt::format(
          "motion: unknown '{}' (expected forward, backward, turn-left, "
          "turn-right, sidewind-left, sidewind-right, roll, stop)",
          command.motion));
    }
    next.SetMotion(*motion, command.strength);
    what += fmt::format(" motion {} {}", ToString(*motion), command.strength);
  }
  if (command.has_direction) {
    next.SetDirection(command.forward, command.turn);
    what += fmt::format(" direction forward {} turn {}", command.forward,
                        command.turn);
  }
  if (what.empty()) {
    throw std::invalid_argument(
        "empty command (no gait, parameters, motion or direction)");
  }
  *controller = std::move(next);
  return what.substr(1);
}

std::string DescribeGaitCommand(const gait_command_t& command) {
  std::vector<std::string> parts;
  if (!command.gait.empty()) parts.push_back("gait " + command.gait);
  if (command.has_parameters) {
    parts.push_back(
        fmt::format("parameters [{:g}]", fmt::join(command.parameters, ", ")));
  }
  if (!command.motion.empty()) {
    parts.push_back(
        fmt::format("motion {} {:.2f}", command.motion, command.strength));
  }
  if (command.has_direction) {
    parts.push_back(fmt::format("direction forward {:.2f} turn {:.2f}",
                                command.forward, command.turn));
  }
  return parts.empty() ? "nothing" : fmt::format("{}", fmt::join(parts, ", "));
}

}  // namespace mrsim
