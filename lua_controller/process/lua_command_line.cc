#include "lua_controller/process/lua_command_line.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "gait_controller/process/joint_axes_spec.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "sim_core/scenario_xml.h"

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
  app.add_option("--robot", robot, "Robot name (as in the scenario)")
      ->required();
  app.add_option("--script", script_path,
                 "Lua file defining step(t, state) (docs/gait.md); default: "
                 "the script saved in --scenario (<run><luaScript>)");
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  AddAuthFlags(app, auth);
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--scenario", scenario_path,
                 "Scenario file mrsim-sim runs (gives state.axes; without it "
                 "or --axes, pitch-yaw is assumed)");
  app.add_option("--axes", axes_text,
                 "Joint axes instead of --scenario: pitch, yaw, pitch-yaw, "
                 "yaw-pitch or P/Y per joint");
  app.add_option("--rate", options.rate,
                 "Control rate in Hz of sim time (0: answer every state)")
      ->capture_default_str();
  app.add_option("--name", name,
                 "Sender name (what mrsim-sim --controllers lists); default "
                 "lua-<robot>");
  app.add_flag("--exit-with-sim", options.exit_with_sim,
               "Exit when the simulator stops or has been silent for 5 s");
  app.add_flag("--check", check_only,
               "Only load the script: report a syntax error with its line "
               "(exit 2) or say it is fine (exit 0)");
}

void LuaCommandLine::Finish() {
  options.robot = robot;
  options.sender = name.empty() ? "lua-" + robot : name;
  script = script_path.empty() ? LoadScenarioLuaScript(scenario_path)
                               : LoadLuaScriptFile(script_path);
  try {
    if (!scenario_path.empty() && !axes_text.empty()) {
      throw std::invalid_argument("give --scenario or --axes, not both");
    }
    if (!scenario_path.empty()) {
      const auto axes = ScenarioJointAxes(scenario_path, robot);
      axes_for = [axes](int) { return axes; };
    } else {
      if (axes_text.empty() && !check_only) {
        warning =
            "warning: no --scenario or --axes: state.axes assumes "
            "alternating pitch-yaw joints, pitch first";
      }
      const JointAxesSpec spec(axes_text.empty() ? "pitch-yaw" : axes_text);
      axes_for = [spec](int n) { return spec.Expand(n); };
    }
    if (!(options.rate >= 0)) {
      throw std::invalid_argument("--rate must be >= 0");
    }
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
}

std::string LuaCommandLine::StartLine() const {
  return "mrsim-lua: robot " + options.robot + ", sender " + options.sender +
         ", script " +
         (script_path.empty() ? "saved in " + scenario_path : script_path) +
         ", listening on " + StateChannel(options.prefix, options.robot);
}

}  // namespace mrsim
