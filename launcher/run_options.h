// How a design is run: the simulator and who drives its robots (one
// mrsim-gait or mrsim-lua per robot, or an external controller the
// simulator waits for), as the command lines a user could type. One plan
// for every program that starts a run: the studio's Run button
// (studio/live/live_runner.h) and `mrsim run FILE` (design_run.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/clock_mode.h"
#include "launcher/launch_file.h"
#include "lcmtypes/runtime/channels.h"
#include "sim_core/scenario/run_settings.h"

namespace mrsim {

struct RunOptions {
  std::string scenario_path;        // a saved scenario file
  std::vector<std::string> robots;  // one mrsim-gait each
  std::string lcm_url;              // empty: LCM's default
  std::string prefix = kDefaultChannelPrefix;
  ClockMode clock = ClockMode::kRealtime;
  double rate = 100;             // Hz
  double speed = 1;              // real-time factor (realtime clock)
  std::string gait = "forward";  // each robot's starting gait
  // Who drives the robots: kGait (mrsim-gait each), kLua (mrsim-lua each,
  // running lua_script) or kExternal (nothing started: mrsim-sim runs in
  // lockstep waiting for the controller named external_name).
  ControllerKind controller = ControllerKind::kGait;
  std::string lua_script;     // a .lua file, for kLua
  std::string external_name;  // for kExternal
  bool paused = false;
  // For mrsim-sim: the sim time to stop at (0: until stopped), where to
  // write a checkpoint when it stops ("": none), and whether to run parts
  // that overlap at the start.
  double duration = 0;
  std::string checkpoint_on_exit;
  bool allow_overlap = false;
};

// The clock, rate, speed, controller, gait and external name of a
// design's saved run settings (<run>); none saved: RunOptions' defaults
// (as mrsim-sim's). The Lua script is text in the settings and a file in
// RunOptions: the caller writes it where it wants it.
RunOptions RunOptionsFromSettings(const std::optional<RunSettings>& run);

// When `run` carries a tuned gait (RunSettings::tuned_gait) and the
// controller is the gait: checks it as mrsim-gait will read it (throws
// GaitFileError naming `source`, e.g. "case.xml: <run><tunedGait>"),
// writes it to `path` and points o->gait at that file, so the robots start
// with it. Returns whether it did.
bool UseTunedGait(const std::optional<RunSettings>& run,
                  const std::string& source, const std::string& path,
                  RunOptions* o);

// The LCM flags every process of the run takes: --lcm-url (when one is
// set) and --prefix.
std::vector<std::string> RunLcmArgs(const RunOptions& options);

// The processes a run starts, in start order: the controllers first so
// they hear the first state, then mrsim-sim (required: its end ends the
// run). Throws std::invalid_argument for options that no run could use
// (no scenario, unknown clock, rate or speed not positive, no Lua script,
// a bad external controller name).
std::vector<ProcessSpec> RunProcessSpecs(const RunOptions& options);

}  // namespace mrsim
