// mrsim-camera: pictures the scenario's robot cameras from the simulator's
// states and publishes them as camera_image_t (docs/camera.md). The logic
// is CameraNode, wired to LCM by CameraServer.
#include <CLI/CLI.hpp>
#include <iostream>

#include "camera/camera_server.h"
#include "camera/process/camera_command_line.h"
#include "camera/state_camera_renderer.h"
#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario/scenario_xml.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-camera: publish what the scenario's cameras see"};
  mrsim::CameraCommandLine flags;
  flags.AddFlags(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    flags.Finish();
    const mrsim::Scenario scenario =
        mrsim::ReadScenarioFile(flags.scenario_path);
    mrsim::StateCameraRenderer renderer(scenario);
    mrsim::CameraNode node(flags.options, &renderer, mrsim::WallClock::now());
    mrsim::InstallStopHandlers();
    mrsim::SignedLcm lcm(flags.lcm_url, flags.auth.Load(),
                         mrsim::WarnLines(std::cerr, "mrsim-camera"));
    if (!lcm.good()) {
      std::cerr << "mrsim-camera: " << mrsim::CannotOpenLcm(flags.lcm_url)
                << "\n";
      return 1;
    }
    mrsim::CameraServer server(lcm, node);
    std::cerr << flags.StartLine(node) << std::endl;
    server.Run([] { return mrsim::StopRequested(); }, std::cerr);
    std::cerr << "mrsim-camera: " << node.Summary() << std::endl;
    return node.gave_up() ? 1 : 0;
  } catch (const mrsim::UsageError& e) {
    std::cerr << "mrsim-camera: " << e.what() << "\n";
    return 2;
  } catch (const mrsim::ScenarioError& e) {
    std::cerr << "mrsim-camera: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "mrsim-camera: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-camera: " << e.what() << "\n";
    return 1;
  }
}
