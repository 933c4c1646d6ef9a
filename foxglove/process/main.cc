// mrsim-foxglove: serves a running simulation to Foxglove (and Lichtblick)
// over the Foxglove WebSocket protocol: the robots in 3-D, every mrsim
// channel as JSON, sim time, and the simulator's controls as services.
// The work is in foxglove_command.h and foxglove/foxglove_server.h.
#include <cstdio>
#include <stdexcept>

#include "CLI/CLI.hpp"
#include "common/cli_exit.h"
#include "foxglove/process/foxglove_command.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Serves a running mrsim simulation to Foxglove / Lichtblick over the "
      "Foxglove WebSocket protocol (connect to ws://HOST:PORT)."};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-foxglove"));
  mrsim::FoxgloveCommand command;
  mrsim::AddFoxgloveFlags(app, command);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    mrsim::InstallStopHandlers();
    mrsim::SignedLcm lcm(
        command.lcm_url, command.auth.Load(), [](const std::string& line) {
          std::fprintf(stderr, "mrsim-foxglove: %s\n", line.c_str());
        });
    return mrsim::RunFoxglove(command, lcm, stderr);
  } catch (const mrsim::UsageError& e) {
    std::fprintf(stderr, "mrsim-foxglove: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrsim-foxglove: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-foxglove: error: %s\n", e.what());
    return 1;
  }
}
