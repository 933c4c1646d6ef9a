#include "studio/live/saved_run.h"

namespace mrsim::studio {

RunSettings SettingsFromRunOptions(const RunOptions& o,
                                   const std::string& lua_source,
                                   const std::string& tuned_gait) {
  RunSettings run;
  run.clock = o.clock;
  run.rate = o.rate;
  run.speed = o.speed;
  run.controller = o.controller;
  run.gait = o.gait;
  run.external_name = o.external_name;
  if (o.controller == ControllerKind::kLua) run.lua_script = lua_source;
  if (o.controller == ControllerKind::kGait) run.tuned_gait = tuned_gait;
  return run;
}

}  // namespace mrsim::studio
