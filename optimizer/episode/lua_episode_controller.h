// A Lua script (--controller lua:FILE) as an episode's controller: a fresh
// sandboxed LuaScript per episode, with the mrsim-lua limits, its declared
// parameters set from the genome's genes of the same names, so episodes
// are independent and the same genome gives the same episode anywhere.
#pragma once

#include <memory>
#include <vector>

#include "lua_controller/lua_script.h"
#include "optimizer/episode/controller_spec.h"
#include "optimizer/episode/episode_controller.h"

namespace mrsim {

class LuaEpisodeController : public EpisodeController {
 public:
  // Throws ControllerError with the script's message when it does not
  // load.
  LuaEpisodeController(const ControllerSpec& controller, const GenomeSpec& spec,
                       const Genome& genome, const std::vector<Axis>& axes);

  const std::vector<double>& Targets(double t,
                                     const RobotState& state) override;

 private:
  std::unique_ptr<LuaScript> script_;
  LuaRobotState input_;  // reused each period
  std::vector<double> targets_;
};

}  // namespace mrsim
