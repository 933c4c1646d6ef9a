// mrsim-log: writes every mrsim channel (or the chosen ones) to one CSV per
// channel or one MCAP file, live from LCM or from an .lcmlog file, reports
// sequence gaps and optionally draws plots when it stops. The work is in
// log_command.h.
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <memory>

#include "CLI/CLI.hpp"
#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "logger/process/log_command.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Writes mrsim LCM channels to one CSV per channel (DIR/<channel>.csv) "
      "or one MCAP file (--mcap), live or from an .lcmlog file, and reports "
      "sequence gaps."};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-log"));
  mrsim::LogCommand command;
  mrsim::AddLogFlags(app, command);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    const mrsim::LogPlan plan = mrsim::PlanLog(command);
    mrsim::InstallStopHandlers();
    std::unique_ptr<mrsim::SignedLcm> lcm;
    if (command.from_log.empty()) {
      lcm = std::make_unique<mrsim::SignedLcm>(
          mrsim::LcmUrlWithReceiveBuffer(command.lcm_url,
                                         command.recv_buf_size),
          command.auth.Load(), [](const std::string& line) {
            std::fprintf(stderr, "mrsim-log: %s\n", line.c_str());
          });
    }
    return mrsim::RunLogCommand(command, plan, lcm.get(), stderr);
  } catch (const mrsim::UsageError& e) {  // the key file
    std::fprintf(stderr, "mrsim-log: %s\n", e.what());
    return 2;
  } catch (const mrsim::LogInputError& e) {
    std::fprintf(stderr, "mrsim-log: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-log: error: %s\n", e.what());
    return 1;
  }
}
