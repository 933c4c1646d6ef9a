#include "lua_controller/process/lua_command_line.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {

std::unique_ptr<LuaScript> LoadLuaScriptFile(const std::string& path,
                                             LuaLimits limits) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError("--script: cannot read " + path);
  std::string source;
  source.resize(limits.max_source_bytes + 1);
  in.read(source.data(), static_cast<std::streamsize>(source.size()));
  source.resize(static_cast<size_t>(in.gcount()));
  if (source.size() > limits.max_source_bytes) {
    throw UsageError("--script: " + path + " is longer than " +
                     std::to_string(limits.max_source_bytes) + " bytes");
  }
  // Lua cuts chunk names at 60 characters: messages name the file alone.
  return std::make_unique<LuaScript>(
      source, std::filesystem::path(path).filename().string(), limits);
}

std::unique_ptr<LuaScript> LoadScenarioLuaScript(const std::string& path,
                                                 LuaLimits limits) {
  Scenario scenario;
  try {
    scenario = ReadScenarioFile(path);
  } catch (const std::exception& e) {
    throw UsageError(std::string("--scenario: ") + e.what());
  }
  if (!scenario.run || scenario.run->lua_script.empty()) {
    throw UsageError("no --script, and " + path +
                     " carries no Lua script (<run><luaScript>): give "
                     "--script FILE");
  }
  if (scenario.run->lua_script.size() > limits.max_source_bytes) {
    throw UsageError("--scenario: the Lua script in " + path +
                     " is longer than " +
                     std::to_string(limits.max_source_bytes) + " bytes");
  }
  return std::make_unique<LuaScript>(scenario.run->lua_script, "luaScript",
                                     limits);
}

void LuaCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-lua"));
  controller.AddFlags(
      app, {&options.prefix, &options.rate, &options.exit_with_sim},
      {"state.axes", "Control rate in Hz of sim time (0: answer every state)",
       "Exit when the simulator stops or has been silent for 5 s"});
  app.add_option("--script", script_path,
                 "Lua file defining step(t, state) (docs/gait.md); default: "
                 "the script saved in --scenario (<run><luaScript>)");
  app.add_option("--camera-sender", options.camera_sender,
                 "Sender name of the camera process (mrsim-camera) whose "
                 "answers say a state's pictures were all sent (docs/lua.md)")
      ->capture_default_str();
  app.add_flag("--check", check_only,
               "Only load the script: report a syntax error with its line "
               "(exit 2) or say it is fine (exit 0)");
}

void LuaCommandLine::Finish() {
  script = script_path.empty() ? LoadScenarioLuaScript(controller.scenario_path)
                               : LoadLuaScriptFile(script_path);
  // --check only loads the script: no warning about the axes it does not use.
  controller.Finish(check_only ? ""
                               : "warning: no --scenario or --axes: "
                                 "state.axes assumes alternating pitch-yaw "
                                 "joints, pitch first");
  options.robot = controller.robot;
  options.sender = controller.sender;
  if (!check_only && !controller.scenario_path.empty()) {
    // The robot's cameras: in lockstep the node then waits for the camera
    // process from the first state (docs/lua.md, "Cameras").
    try {
      options.cameras = -1;
      for (const Robot& r : ReadScenarioFile(controller.scenario_path).robots) {
        if (r.name != options.robot) continue;
        options.cameras = 0;
        for (const SensorModule& m : r.sensor_modules) {
          options.cameras += static_cast<int>(m.cameras.size());
        }
      }
    } catch (const std::exception&) {
      options.cameras = -1;  // the axes' reading says what is wrong
    }
  }
}

std::string LuaCommandLine::StartLine() const {
  return "mrsim-lua: robot " + options.robot + ", sender " + options.sender +
         ", script " +
         (script_path.empty() ? "saved in " + controller.scenario_path
                              : script_path) +
         ", listening on " + StateChannel(options.prefix, options.robot);
}

}  // namespace mrsim
