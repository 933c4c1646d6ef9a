// mrsim-studio: design a robot in a window with a live preview
// (docs/studio.md). Exit codes: 0, 2 bad input or no display, 1 failure.
#include <atomic>
#include <csignal>
#include <iostream>

#include "common/cli_exit.h"
#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/app/headless_studio.h"
#include "studio/app/studio_flags.h"
#include "studio/app/window_studio.h"
#include "viewer/live_window.h"

static std::atomic<bool> g_stop{false};
static void OnSignal(int) { g_stop = true; }

int main(int argc, char** argv) {
  using namespace mrsim::studio;
  CLI::App cli("mrsim-studio: design a modular robot and its scene");
  StudioFlags flags;
  AddStudioFlags(&cli, &flags);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(cli, e);  // 2 for bad usage, as every tool
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::signal(SIGPIPE, SIG_IGN);  // a tcpq hub gone must not kill the window
  try {
    mrsim::AuthFlags auth{flags.key_file};
    auth.Load();  // a bad key file is said now, not at the first run
    auth.ExportToChildren();
    if (flags.screenshot.empty() && !mrsim::LiveWindow::DisplayAvailable()) {
      throw mrsim::UsageError(
          "no display (DISPLAY is not set); run it on a desktop, under "
          "xvfb-run, or use --screenshot OUT.png");
    }
    const AppOptions options = StartOptions(flags);
    StudioApp app(OpenDesign(flags), options);
    if (!flags.screenshot.empty()) {
      SaveScreenshot(&app, options.width, options.height, flags.screenshot,
                     flags.drag);
    } else {
      RunWindow(&app, options.width, options.height, &g_stop);
    }
  } catch (const mrsim::ScenarioError& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 2;
  } catch (const mrsim::UsageError& e) {  // key file, display, --select
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
