// mrsim-nn: drives one robot of mrsim-sim with a neural-network controller
// (docs/nn.md); the logic is NnNode, wired to LCM by NnServer.
#include <CLI/CLI.hpp>
#include <iostream>

#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "nn_controller/process/nn_command_line.h"
#include "nn_controller/process/nn_server.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-nn: drive one robot of mrsim-sim with a neural network"};
  mrsim::NnCommandLine flags;
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
      std::cout << flags.net_path << ": OK\n";
      return 0;
    }
    mrsim::InstallStopHandlers();
    mrsim::SignedLcm lcm(ctl.lcm_url, ctl.auth.Load(),
                         mrsim::WarnLines(std::cerr, "mrsim-nn"));
    if (!lcm.good()) {
      std::cerr << "mrsim-nn: " << mrsim::CannotOpenLcm(ctl.lcm_url) << "\n";
      return 1;
    }
    mrsim::NnServer server(lcm, flags.options,
                           mrsim::NnNode(flags.options, flags.net->network,
                                         mrsim::WallClock::now()));
    std::cerr << flags.StartLine() << std::endl;
    server.Run([] { return mrsim::StopRequested(); }, std::cerr);
    const std::string& error = server.node().error();
    if (!error.empty()) std::cerr << "mrsim-nn: error: " << error << "\n";
    std::cerr << "mrsim-nn: " << server.node().Summary() << std::endl;
    if (!error.empty()) return 2;
    return server.node().gave_up() ? 1 : 0;
  } catch (const mrsim::NetworkFileError& e) {
    std::cerr << "mrsim-nn: error: " << e.what() << "\n";
    return 2;
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-nn: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-nn: " << e.what() << "\n";
    return 1;
  }
}
