// mrsim-lua: drives one robot of mrsim-sim with a Lua script (docs/gait.md,
// "Lua controllers"); the logic is LuaNode, wired to LCM by LuaServer.
#include <CLI/CLI.hpp>
#include <iostream>

#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lua_controller/process/lua_command_line.h"
#include "lua_controller/process/lua_server.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-lua: drive one robot of mrsim-sim with a Lua script"};
  mrsim::LuaCommandLine flags;
  const mrsim::ControllerFlags& ctl = flags.controller;
  flags.AddFlags(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    flags.Finish();
    if (flags.check_only) {
      std::cout << flags.script_path << ": OK\n";
      return 0;
    }
    if (!ctl.warning.empty()) std::cerr << "mrsim-lua: " << ctl.warning << "\n";
    mrsim::InstallStopHandlers();
    mrsim::SignedLcm lcm(ctl.lcm_url, ctl.auth.Load(),
                         mrsim::WarnLines(std::cerr, "mrsim-lua"));
    if (!lcm.good()) {
      std::cerr << "mrsim-lua: " << mrsim::CannotOpenLcm(ctl.lcm_url) << "\n";
      return 1;
    }
    mrsim::LuaServer server(
        lcm, flags.options,
        mrsim::LuaNode(flags.options, std::move(flags.script), ctl.axes_for,
                       mrsim::WallClock::now()));
    std::cerr << flags.StartLine() << std::endl;
    server.Run([] { return mrsim::StopRequested(); }, std::cerr);
    const std::string& error = server.node().error();
    if (!error.empty()) std::cerr << "mrsim-lua: error: " << error << "\n";
    std::cerr << "mrsim-lua: " << server.node().Summary() << std::endl;
    if (!error.empty()) return 2;
    return server.node().gave_up() ? 1 : 0;
  } catch (const mrsim::LuaScriptError& e) {
    std::cerr << "mrsim-lua: error: " << e.what() << "\n";
    return 2;
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-lua: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-lua: " << e.what() << "\n";
    return 1;
  }
}
