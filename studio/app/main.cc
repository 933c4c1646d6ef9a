// mrsim-studio: design a robot in a window with a live preview
// (docs/studio.md). Exit codes: 0, 2 bad input or no display, 1 failure.
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <iostream>

#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "sim_core/scenario_xml.h"
#include "studio/app/headless_studio.h"
#include "studio/app/window_studio.h"
#include "viewer/live_window.h"

namespace {
std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }
}  // namespace

int main(int argc, char** argv) {
  using namespace mrsim::studio;
  CLI::App cli("mrsim-studio: design a modular robot and its scene");
  std::string scenario, screenshot;
  AppOptions options;
  cli.add_option("SCENARIO", scenario, "Scenario file to open (or create)");
  cli.add_option("--screenshot", screenshot,
                 "Render the window once off-screen to this PNG and exit");
  cli.add_option("--width", options.width, "Window width")
      ->capture_default_str();
  cli.add_option("--height", options.height, "Window height")
      ->capture_default_str();
  cli.add_option("--ui-scale", options.ui_scale,
                 "Text and panel size (1: 15 px text; default: the monitor's "
                 "content scale)")
      ->check(CLI::Range(0.0f, 4.0f));
  cli.add_option("--layout-dump", options.layout_dump,
                 "Write widget rectangles and state here (for tests)");
  std::string key_file;
  cli.add_option("--key-file", key_file,
                 "Sign the live session's messages, and those of the "
                 "processes it starts, with this key (default: "
                 "$MRSIM_KEY_FILE; docs/security.md)");
  cli.set_version_flag("--version", mrsim::VersionLine("mrsim-studio"));
  CLI11_PARSE(cli, argc, argv);
  try {
    mrsim::AuthFlags auth{key_file};
    auth.Load();  // a bad key file is said now, not at the first run
    auth.ExportToChildren();
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 2;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::signal(SIGPIPE, SIG_IGN);  // a tcpq hub gone must not kill the window
  if (screenshot.empty() && !mrsim::LiveWindow::DisplayAvailable()) {
    std::cerr << "mrsim-studio: no display (DISPLAY is not set); run it on a "
                 "desktop, under xvfb-run, or use --screenshot OUT.png\n";
    return 2;
  }
  try {
    StudioApp app(scenario.empty() ? Design() : Design::Open(scenario),
                  options);
    if (!screenshot.empty()) {
      SaveScreenshot(&app, options.width, options.height, screenshot);
    } else {
      RunWindow(&app, options.width, options.height, &g_stop);
    }
  } catch (const mrsim::ScenarioError& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-studio: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
