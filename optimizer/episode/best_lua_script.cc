#include "optimizer/episode/best_lua_script.h"

#include <fmt/format.h>

namespace mrsim {

std::string BestLuaScript(const ControllerSpec& controller,
                          const GenomeSpec& spec, const Genome& best) {
  std::string values;
  for (int i = 0; i < spec.size(); ++i) {
    const std::string& name = spec.genes[i].name;
    if (GeneRangeOf(name)) continue;  // a built-in (body) gene
    // 17 significant digits: Lua reads back the very same double.
    values += fmt::format("    {} = {:.17g},\n", name, best[i]);
  }
  std::string out = controller.source;
  if (!out.empty() && out.back() != '\n') out += "\n";
  out += fmt::format(
      "\n-- Written by mrsim-opt from {}: the best values found replace the\n"
      "-- declared start values, so P holds them when this runs\n"
      "-- (mrsim-lua --script best_controller.lua ...).\n"
      "do\n"
      "  local best = {{\n{}  }}\n"
      "  for _, p in ipairs(params) do\n"
      "    if best[p.name] ~= nil then p.start = best[p.name] end\n"
      "  end\n"
      "end\n",
      controller.name, values);
  return out;
}

}  // namespace mrsim
