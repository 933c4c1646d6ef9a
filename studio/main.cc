// mrsim-studio: design a robot in a window with a live preview
// (docs/studio.md). Exit codes: 0, 2 bad input or no display, 1 failure.
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <iostream>

#include "lcmtypes/runtime/version.h"
#include "sim_core/scenario_xml.h"
#include "studio/headless_studio.h"
#include "studio/window_studio.h"
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
  cli.add_option("--layout-dump", options.layout_dump,
                 "Write widget rectangles and state here (for tests)");
  cli.set_version_flag("--version", mrsim::VersionLine("mrsim-studio"));
  CLI11_PARSE(cli, argc, argv);
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
