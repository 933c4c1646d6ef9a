#include "sim_core/sim_process/sim_command_line.h"

#include <fmt/format.h>

#include "common/enum_option.h"
#include "lcmtypes/runtime/version.h"
#include "sim_core/checkpoint.h"
#include "sim_core/scenario_xml.h"

namespace mrsim {

void SimCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-sim"));
  app.add_option("scenario", scenario_path,
                 "Scenario XML file (optional with --load-checkpoint)");
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  AddAuthFlags(app, auth);
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  AddEnumOption(app, "--clock", &options.clock, ClockModes(),
                "how simulated time runs against the wall clock");
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
  app.add_option("--actuation-delay", options.actuation_delay,
                 "Lockstep: the answer to state k acts from period k+DELAY "
                 "(0 strict, 1 pipelined; docs/sim.md)")
      ->capture_default_str();
  app.add_flag("--no-spin", no_spin,
               "Lockstep: no thread spinning at idle priority for the next "
               "state to send (uses no spare CPU; strict lockstep slower; "
               "docs/sim.md)");
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
}

void SimCommandLine::Finish() {
  try {
    options.publish_state = !no_state;
    options.spin = !no_spin;
    options.Validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (scenario_path.empty() && load_checkpoint.empty()) {
    throw UsageError("expected a SCENARIO file or --load-checkpoint PATH");
  }
}

std::string SimCommandLine::LoadLine(const Physics& physics) const {
  if (load_checkpoint.empty()) return "";
  std::string robots;
  for (int r = 0; r < physics.robot_count(); ++r) {
    robots += fmt::format("{}{} ({} joints)", r == 0 ? "" : ", ",
                          physics.robot_name(r), physics.joint_count(r));
  }
  return fmt::format(
      "mrsim-sim: loaded checkpoint {}: {} robot{}{}{}, continuing from sim "
      "time {:.3f} s{}",
      load_checkpoint, physics.robot_count(),
      physics.robot_count() == 1 ? "" : "s", robots.empty() ? "" : ": ", robots,
      physics.time(),
      scenario_path.empty() ? "" : " (same scenario as " + scenario_path + ")");
}

std::unique_ptr<Physics> SimCommandLine::LoadPhysics() const {
  std::unique_ptr<Physics> physics;
  try {
    if (!load_checkpoint.empty()) physics = LoadCheckpoint(load_checkpoint);
  } catch (const CheckpointError& e) {
    throw UsageError(std::string("--load-checkpoint: ") + e.what());
  }
  if (physics && options.duration > 0 &&
      options.duration <= physics->time() + 0.5 * physics->timestep()) {
    // --duration is a sim time, counted from 0, not from the checkpoint.
    throw UsageError(fmt::format(
        "--duration {} ends before the checkpoint's sim time {:.3f} s: "
        "nothing would run (--duration is the sim time to stop at; e.g. "
        "--duration {:g} runs {:g} s more)",
        options.duration, physics->time(), physics->time() + options.duration,
        options.duration));
  }
  if (scenario_path.empty()) return physics;
  try {
    Scenario scenario = ReadScenarioFile(scenario_path);
    if (!physics) return std::make_unique<Physics>(scenario);
    Scenario saved = physics->scenario();
    saved.base_dir = scenario.base_dir;
    if (!(saved == scenario)) {
      throw UsageError("--load-checkpoint " + load_checkpoint +
                       " holds a different scenario than " + scenario_path +
                       " (leave SCENARIO out to use the checkpoint's)");
    }
    return physics;
  } catch (const ScenarioError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace mrsim
