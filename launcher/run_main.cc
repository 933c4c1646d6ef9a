// mrsim-run (`mrsim run FILE`): runs a saved design headless with the
// controller saved in it, then prints how far it moved (design_run.h).
#include <CLI/CLI.hpp>
#include <cstdio>

#include "common/cli_exit.h"
#include "common/version.h"
#include "launcher/design_run.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/export/overlap_check.h"

int main(int argc, char** argv) {
  CLI::App app{
      "mrsim run: runs a saved design headless with the controller saved "
      "in it (gait, Lua script or external), logs it, and says how far it "
      "moved"};
  app.set_version_flag("--version",
                       std::string("mrsim-run ") + mrsim::kVersion);
  mrsim::DesignRunFlags flags;
  mrsim::AddDesignRunFlags(app, flags);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    const mrsim::DesignRun run(argv[0], flags);
    for (const std::string& w : run.warnings()) {
      std::fprintf(stderr, "mrsim run: %s\n", w.c_str());
    }
    mrsim::InstallStopHandlers();
    const int code = run.Run([] { return mrsim::StopRequested(); }, stdout);
    std::printf("%s\n", run.Summary().c_str());
    return code;
  } catch (const mrsim::OverlapError& e) {
    std::fprintf(stderr, "mrsim run: %s\n%s\n", e.what(),
                 mrsim::kAllowOverlapHint);
    return 2;
  } catch (const mrsim::ScenarioError& e) {
    std::fprintf(stderr, "mrsim run: %s\n", e.what());
    return 2;
  } catch (const mrsim::UsageError& e) {
    std::fprintf(stderr, "mrsim run: %s\n", e.what());
    return 2;
  } catch (const mrsim::LaunchError& e) {
    std::fprintf(stderr, "mrsim run: %s\n", e.what());
    return 2;
  } catch (const mrsim::CheckpointError& e) {
    std::fprintf(stderr, "mrsim run: no summary: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim run: %s\n", e.what());
    return 1;
  }
}
