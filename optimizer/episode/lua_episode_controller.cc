#include "optimizer/episode/lua_episode_controller.h"

#include "lua_controller/lua_robot_state_fill.h"

namespace mrsim {

LuaEpisodeController::LuaEpisodeController(const ControllerSpec& controller,
                                           const GenomeSpec& spec,
                                           const Genome& genome,
                                           const std::vector<Axis>& axes) {
  try {
    script_ = std::make_unique<LuaScript>(controller.source, controller.name);
    // A parameter the genome does not name keeps its start value.
    std::vector<double> values;
    for (const LuaParameter& p : script_->parameters()) {
      const int i = spec.Find(p.name);
      values.push_back(i >= 0 ? genome[i] : p.start);
    }
    script_->SetParameters(values);
  } catch (const std::exception& e) {
    throw ControllerError(e.what());
  }
  for (Axis a : axes) input_.axes.push_back(a == Axis::kYaw ? "yaw" : "pitch");
}

const std::vector<double>& LuaEpisodeController::Targets(
    double t, const RobotState& state) {
  FillLuaRobotState(state, &input_);
  try {
    targets_ = script_->Step(t, input_);
  } catch (const std::exception& e) {
    throw ControllerError(e.what());
  }
  return targets_;
}

}  // namespace mrsim
