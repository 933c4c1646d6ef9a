// mrsim-sim: runs a scenario headless and serves it over LCM (docs/sim.md).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "lcmtypes/runtime/stop_signal.h"
#include "sim_core/checkpoint.h"
#include "sim_core/physics.h"
#include "sim_core/scenario_xml.h"
#include "sim_core/sim_process/sim_server.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-sim: simulate a scenario and serve it over LCM"};
  std::string scenario_path;
  std::string lcm_url;
  std::string clock = "realtime";
  std::string load_checkpoint;
  mrsim::SimOptions options;
  bool no_state = false;
  app.add_option("scenario", scenario_path,
                 "Scenario XML file (optional with --load-checkpoint)");
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--clock", clock, "realtime | fast | lockstep")
      ->capture_default_str();
  app.add_option("--speed", options.speed,
                 "Real-time factor for the realtime clock")
      ->capture_default_str();
  app.add_option("--rate", options.rate,
                 "State publication rate = control rate (Hz)")
      ->capture_default_str();
  app.add_option("--controllers", options.controllers,
                 "Lockstep: sender names to wait for")
      ->delimiter(',');
  app.add_option("--lockstep-timeout", options.lockstep_timeout,
                 "Lockstep: seconds before warning about a late controller")
      ->capture_default_str();
  app.add_option("--duration", options.duration,
                 "Stop after this many sim seconds (0 = run until stopped)")
      ->capture_default_str();
  app.add_flag("--paused", options.paused, "Start paused");
  app.add_flag("--no-state", no_state,
               "Do not publish robot states (batch runs; not with lockstep)");
  app.add_option("--checkpoint-on-exit", options.checkpoint_on_exit,
                 "Write a checkpoint here when stopping");
  app.add_option("--load-checkpoint", load_checkpoint,
                 "Start from this checkpoint (its scenario and state)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    options.clock = mrsim::ParseClockMode(clock);
    options.publish_state = !no_state;
    options.Validate();
    if (scenario_path.empty() && load_checkpoint.empty()) {
      throw std::invalid_argument(
          "expected a SCENARIO file or --load-checkpoint PATH");
    }
  } catch (const std::invalid_argument& e) {
    std::cerr << "mrsim-sim: " << e.what() << "\n";
    return 2;
  }

  try {
    mrsim::InstallStopHandlers();
    std::unique_ptr<mrsim::Physics> physics;
    try {
      if (!load_checkpoint.empty()) {
        physics = mrsim::LoadCheckpoint(load_checkpoint);
      }
      if (!scenario_path.empty()) {
        mrsim::Scenario scenario = mrsim::ReadScenarioFile(scenario_path);
        if (physics) {
          mrsim::Scenario saved = physics->scenario();
          saved.base_dir = scenario.base_dir;
          if (!(saved == scenario)) {
            std::cerr << "mrsim-sim: --load-checkpoint " << load_checkpoint
                      << " holds a different scenario than " << scenario_path
                      << " (leave SCENARIO out to use the checkpoint's)\n";
            return 2;
          }
        } else {
          physics = std::make_unique<mrsim::Physics>(scenario);
        }
      }
    } catch (const mrsim::ScenarioError& e) {
      std::cerr << "mrsim-sim: " << e.what() << "\n";
      return 2;
    } catch (const mrsim::CheckpointError& e) {
      std::cerr << "mrsim-sim: --load-checkpoint: " << e.what() << "\n";
      return 2;
    }
    lcm::LCM lcm(lcm_url);
    if (!lcm.good()) {
      std::cerr << "mrsim-sim: cannot open LCM '" << lcm_url
                << "' (no multicast route? see docs/sim.md)\n";
      return 1;
    }
    const double timestep = physics->timestep();
    const int robots = physics->robot_count();
    mrsim::SimServer server(lcm, std::move(physics), options, std::cerr);
    const double wanted = 1.0 / options.rate;
    if (std::abs(server.period() - wanted) > 1e-9) {
      std::cerr << "mrsim-sim: note: control period " << server.period()
                << " s (" << server.steps_per_period() << " physics steps of "
                << timestep << " s) instead of 1/" << options.rate << " s\n";
    }
    std::cerr << "mrsim-sim: " << robots << " robot(s), clock " << clock << ", "
              << 1.0 / server.period() << " Hz control, "
              << server.steps_per_period() << " steps of " << timestep
              << " s per period, prefix " << options.prefix
              << (options.paused ? ", paused" : "") << "\n";
    const mrsim::StopReason reason =
        server.Run([] { return mrsim::StopRequested(); });
    std::cout << server.Summary(reason) << std::endl;
    return server.exit_checkpoint_error().empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mrsim-sim: " << e.what() << "\n";
    return 1;
  }
}
