// mrsim-sim: runs a scenario headless and serves it over LCM (docs/sim.md).
#include <CLI/CLI.hpp>
#include <iostream>
#include <lcm/lcm-cpp.hpp>

#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "sim_core/sim_process/sim_command_line.h"
#include "sim_core/sim_process/sim_server.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-sim: simulate a scenario and serve it over LCM"};
  mrsim::SimCommandLine flags;
  flags.AddFlags(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    flags.Finish();
    mrsim::InstallStopHandlers();
    auto physics = flags.LoadPhysics();
    const std::string loaded = flags.LoadLine(*physics);
    if (!loaded.empty()) std::cerr << loaded << "\n";
    for (const std::string& w : flags.warnings) std::cerr << w << "\n";
    if (!flags.run_note.empty()) std::cerr << flags.run_note << "\n";
    mrsim::SignedLcm lcm(flags.lcm_url, flags.auth.Load(),
                         mrsim::WarnLines(std::cerr, "mrsim-sim"));
    if (!lcm.good()) {
      std::cerr << "mrsim-sim: " << mrsim::CannotOpenLcm(flags.lcm_url) << "\n";
      return 1;
    }
    mrsim::SimServer server(lcm, std::move(physics), flags.options, std::cerr);
    if (!server.PeriodNote().empty()) std::cerr << server.PeriodNote() << "\n";
    std::cerr << server.StartLine() << "\n";
    const mrsim::StopReason reason =
        server.Run([] { return mrsim::StopRequested(); });
    std::cout << server.node().Summary() << std::endl;
    const bool failed = reason == mrsim::StopReason::kPhysicsFailed ||
                        !server.exit_checkpoint_error().empty();
    return failed ? 1 : 0;
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-sim: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-sim: " << e.what() << "\n";
    return 1;
  }
}
