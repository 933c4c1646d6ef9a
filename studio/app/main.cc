// mrsim-studio: design a robot in a window with a live preview
// (docs/studio.md). Exit codes: 0, 2 bad input or no display, 1 failure.
#include <atomic>
#include <csignal>
#include <iostream>

#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario_xml.h"
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
  CLI11_PARSE(cli, argc, argv);
  try {
    mrsim::AuthFlags auth{flags.key_file};
    auth.Load();  // a bad key file is said now, not at the first run
    auth.ExportToChildren();
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 2;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::signal(SIGPIPE, SIG_IGN);  // a tcpq hub gone must not kill the window
  if (flags.screenshot.empty() && !mrsim::LiveWindow::DisplayAvailable()) {
    std::cerr << "mrsim-studio: no display (DISPLAY is not set); run it on a "
                 "desktop, under xvfb-run, or use --screenshot OUT.png\n";
    return 2;
  }
  try {
    const AppOptions& options = flags.options;
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
  } catch (const mrsim::UsageError& e) {  // --select names nothing
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
