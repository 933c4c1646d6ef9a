// mrsim-lua's command line: the flags (CLI11) and what they build (the
// node options, the loaded script, where the joint axes come from), so
// main only parses, wires and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gait_controller/process/controller_flags.h"
#include "lua_controller/lua_script.h"
#include "lua_controller/process/lua_node.h"

namespace mrsim {

struct LuaCommandLine {
  // --robot, --lcm-url, --scenario, --axes, --name, ...; after Finish() its
  // axes_for and warning.
  ControllerFlags controller{"lua"};
  std::string script_path;
  bool check_only = false;
  LuaNodeOptions options;

  // Filled by Finish().
  std::unique_ptr<LuaScript> script;

  void AddFlags(CLI::App& app);
  // Loads the script (throws LuaScriptError with its line) and resolves the
  // joint axes; throws UsageError naming the flag for the rest.
  void Finish();
  std::string StartLine() const;
};

// Reads a script file of at most limits.max_source_bytes and loads it
// (named by its file name in messages). Throws UsageError when it cannot be
// read or is too long, LuaScriptError when it does not load.
std::unique_ptr<LuaScript> LoadLuaScriptFile(const std::string& path,
                                             LuaLimits limits = {});
// The Lua script a scenario file carries in its run settings
// (<run><luaScript>, named "luaScript" in messages). Throws UsageError
// when the file does not read or carries none, LuaScriptError when it
// does not load.
std::unique_ptr<LuaScript> LoadScenarioLuaScript(const std::string& path,
                                                 LuaLimits limits = {});

}  // namespace mrsim
