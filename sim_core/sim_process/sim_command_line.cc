#include "sim_core/sim_process/sim_command_line.h"

#include <fmt/format.h>

#include "common/enum_option.h"
#include "lcmtypes/runtime/version.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {

void SimCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-sim"));
  app.add_option("scenario", scenario_path,
                 "Scenario XML file (optional with --load-checkpoint)");
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  AddAuthFlags(app, auth);
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  clock_flag_ = AddEnumOption(
      app, "--clock", &options.clock, ClockModes(),
      "how simulated time runs against the wall clock (default: the "
      "scenario's <run>, else realtime)");
  speed_flag_ = app.add_option("--speed", options.speed,
                               "Real-time factor for the realtime clock")
                    ->capture_default_str();
  rate_flag_ = app.add_option("--rate", options.rate,
                              "State publication rate = control rate (Hz)")
                   ->capture_default_str();
  controllers_flag_ = app.add_option("--controllers", options.controllers,
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
  app.add_flag("--allow-overlap", allow_overlap,
               "Run even when parts overlap at the start (the physics then "
               "pushes them apart at the first step)");
}

void SimCommandLine::Finish() {
  try {
    options.publish_state = !no_state;
    options.spin = !no_spin;
    options.Validate();
  } catch (const std::invalid_argument& e) {
    // The scenario's saved clock may complete the flags (--controllers
    // with a lockstep clock): ApplyRunSettings checks again.
    if (scenario_path.empty() || clock_flag_ == nullptr ||
        clock_flag_->count() > 0) {
      throw UsageError(e.what());
    }
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

void SimCommandLine::ApplyRunSettings(const Scenario& scenario) {
  if (!scenario.run) {
    try {
      options.Validate();
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    return;
  }
  const RunSettings& run = *scenario.run;
  const auto given = [](const CLI::Option* flag) {
    return flag != nullptr && flag->count() > 0;
  };
  const bool external = run.controller == ControllerKind::kExternal;
  if (!given(clock_flag_)) {
    // An external controller is waited for at every step, as in the studio.
    options.clock = external ? ClockMode::kLockstep : run.clock;
  }
  if (!given(rate_flag_)) options.rate = run.rate;
  if (!given(speed_flag_)) options.speed = run.speed;
  std::vector<std::string> names;
  for (int r = 0; r < static_cast<int>(scenario.robots.size()); ++r) {
    const std::string robot = RobotName(scenario, r);
    names.push_back(
        (run.controller == ControllerKind::kLua ? "lua-" : "gait-") + robot);
  }
  if (external) names = {run.external_name};
  if (!given(controllers_flag_) && options.clock == ClockMode::kLockstep) {
    options.controllers = names;
  }
  try {
    options.Validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string(e.what()) + " (with the run settings of " +
                     scenario_path + ")");
  }
  std::string start;
  if (external) {
    start =
        fmt::format("start the controller named '{}' (lockstep waits for it)",
                    run.external_name);
  } else {
    const bool lua = run.controller == ControllerKind::kLua;
    for (size_t r = 0; r < scenario.robots.size(); ++r) {
      const std::string robot = RobotName(scenario, static_cast<int>(r));
      start += fmt::format("{}`{} --robot {} --scenario {}{} --name {}`",
                           r == 0 ? "" : ", ", lua ? "mrsim-lua" : "mrsim-gait",
                           robot, scenario_path,
                           lua ? "" : " --gait " + run.gait, names[r]);
    }
    start = start.empty() ? "no robot to control" : "start " + start;
  }
  run_note = fmt::format(
      "mrsim-sim: run settings of {}: clock {}, {:g} Hz, controller {}; {}",
      scenario_path, ToString(options.clock), options.rate,
      ToString(run.controller), start);
}

std::unique_ptr<Physics> SimCommandLine::LoadPhysics() {
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
    ScenarioSource source;
    ScenarioReadOptions read;
    read.source_out = &source;
    Scenario scenario = ReadScenarioFile(scenario_path, read);
    ApplyRunSettings(scenario);
    for (const ScenarioWarning& w : ScenarioWarnings(scenario, &source)) {
      warnings.push_back("mrsim-sim: " + w.text);
    }
    if (!physics) {
      physics = std::make_unique<Physics>(scenario);
      // On the model just built, at the file's pose (a checkpoint's parts
      // are where the run left them, not at the start: not checked).
      if (!allow_overlap) {
        RefuseOverlapsInModel(scenario, physics->model(), &source);
      }
      return physics;
    }
    Scenario saved = physics->scenario();
    saved.base_dir = scenario.base_dir;
    if (!(saved == scenario)) {
      throw UsageError("--load-checkpoint " + load_checkpoint +
                       " holds a different scenario than " + scenario_path +
                       " (leave SCENARIO out to use the checkpoint's)");
    }
    return physics;
  } catch (const OverlapError& e) {
    throw UsageError(std::string(e.what()) + "\n" + kAllowOverlapHint);
  } catch (const ScenarioError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace mrsim
