// mrsim-gait: drives one robot of a running mrsim-sim with a sinusoid gait
// (docs/gait.md; the logic is GaitNode, wired to LCM by GaitServer).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>

#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "gait_controller/process/gait_command_line.h"
#include "gait_controller/process/gait_server.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-gait: drive one robot of mrsim-sim with a gait"};
  mrsim::GaitCommandLine flags;
  const mrsim::ControllerFlags& ctl = flags.controller;
  flags.AddFlags(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    flags.Finish(isatty(STDIN_FILENO));
    if (!ctl.warning.empty())
      std::cerr << "mrsim-gait: " << ctl.warning << "\n";
    mrsim::InstallStopHandlers();
    mrsim::SignedLcm lcm(ctl.lcm_url, ctl.auth.Load(),
                         mrsim::WarnLines(std::cerr, "mrsim-gait"));
    if (!lcm.good()) {
      std::cerr << "mrsim-gait: " << mrsim::CannotOpenLcm(ctl.lcm_url) << "\n";
      return 1;
    }
    mrsim::GaitServer server(lcm, flags.options, ctl.axes_for, flags.initial);
    if (!flags.resume.empty()) server.node().Resume(flags.resume);
    std::cerr << flags.StartLine() << std::endl;
    {
      std::unique_ptr<mrsim::RawKeyboard> keys;
      if (flags.keyboard) keys = std::make_unique<mrsim::RawKeyboard>();
      server.Run([] { return mrsim::StopRequested(); }, keys.get(), std::cerr);
    }  // the terminal back to normal before the summary
    // The error first: it is why the run ended.
    const std::string& error = server.node().error();
    if (!error.empty()) std::cerr << "mrsim-gait: " << error << "\n";
    std::cerr << "mrsim-gait: " << server.node().Summary() << std::endl;
    if (!error.empty()) return 2;
    return server.node().gave_up() ? 1 : 0;
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-gait: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-gait: " << e.what() << "\n";
    return 1;
  }
}
