#include "studio/live/saved_run.h"

namespace mrsim::studio {

RunOptions RunOptionsFromSettings(const std::optional<RunSettings>& run) {
  RunOptions o;
  if (!run) return o;
  o.clock = run->clock;
  o.rate = run->rate;
  o.speed = run->speed;
  o.controller = run->controller;
  o.gait = run->gait;
  o.external_name = run->external_name;
  return o;
}

RunSettings SettingsFromRunOptions(const RunOptions& o,
                                   const std::string& lua_source) {
  RunSettings run;
  run.clock = o.clock;
  run.rate = o.rate;
  run.speed = o.speed;
  run.controller = o.controller;
  run.gait = o.gait;
  run.external_name = o.external_name;
  if (o.controller == ControllerKind::kLua) run.lua_script = lua_source;
  return run;
}

}  // namespace mrsim::studio
