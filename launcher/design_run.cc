#include "launcher/design_run.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "common/atomic_file.h"
#include "common/lcm_url.h"
#include "gait_controller/gait_file.h"
#include "launcher/program_locator.h"
#include "launcher/run_options.h"
#include "launcher/run_summary.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

// The run's options: the design's saved <run>, then the flags over them.
RunOptions OptionsOf(const Scenario& s, const std::string& path,
                     const DesignRunFlags& flags) {
  RunOptions o = RunOptionsFromSettings(s.run);
  o.scenario_path = path;
  for (int r = 0; r < static_cast<int>(s.robots.size()); ++r) {
    o.robots.push_back(RobotName(s, r));
  }
  o.lcm_url = ResolveLcmUrl(flags.lcm_url);
  try {
    if (!flags.clock.empty()) o.clock = ParseClockMode(flags.clock);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (flags.speed) o.speed = *flags.speed;
  o.duration = flags.duration;
  o.allow_overlap = flags.allow_overlap;
  return o;
}

// The logger and the viewer, as demo.launch starts them: each may finish
// its work once the simulator stops (a viewer slower than real time
// renders the frames it fell behind on).
std::vector<ProcessSpec> OutputSpecs(const RunOptions& o,
                                     const std::string& out_dir,
                                     const std::string& name) {
  const std::vector<std::string> lcm = RunLcmArgs(o);
  ProcessSpec log;
  log.name = "log";
  log.program = "mrsim-log";
  log.finish_s = 30;
  log.ready_line = "recording channels";
  log.args = {"--out", out_dir + "/csv", "--exit-with-sim"};
  log.args.insert(log.args.end(), lcm.begin(), lcm.end());
  ProcessSpec view;
  view.name = "view";
  view.program = "mrsim-view";
  view.ready_line = "listening on";
  view.finish_s = 600;
  view.args = {o.scenario_path,   "--out",    out_dir + "/" + name + ".mp4",
               "--exit-with-sim", "--camera", "follow"};
  view.args.insert(view.args.end(), lcm.begin(), lcm.end());
  return {log, view};
}

}  // namespace

void AddDesignRunFlags(CLI::App& app, DesignRunFlags& f) {
  app.add_option("FILE", f.file, "Scenario file (its <run> says who drives)")
      ->required();
  app.add_option("--duration", f.duration,
                 "Stop after this many sim seconds (0: until Ctrl-C)")
      ->capture_default_str();
  app.add_option("--out", f.out,
                 "Output folder: csv/, NAME.mp4, final.checkpoint (default: "
                 "out/NAME here)");
  app.add_option("--clock", f.clock,
                 "realtime | fast | lockstep (default: the file's <run>)")
      ->check(CLI::IsMember(ClockModes().Names()));
  app.add_option("--speed", f.speed,
                 "Real-time factor of the realtime clock (default: the "
                 "file's <run>, else 1)");
  app.add_option("--lcm-url", f.lcm_url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else "
                 "udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--without", f.without,
                 "Leave out a process: view, log or a controller");
  app.add_flag("--allow-overlap", f.allow_overlap,
               "Run even when parts overlap at the start");
}

DesignRun::DesignRun(const std::string& argv0, const DesignRunFlags& flags) {
  if (!(flags.duration >= 0)) {
    throw UsageError(fmt::format(
        "--duration {}: expected >= 0 s (0: until Ctrl-C)", flags.duration));
  }
  scenario_path_ = fs::absolute(flags.file).lexically_normal().string();
  ScenarioSource source;
  ScenarioReadOptions read;
  read.source_out = &source;
  scenario_ = ReadScenarioFile(scenario_path_, read);
  for (const ScenarioWarning& w : ScenarioWarnings(scenario_, &source)) {
    warnings_.push_back(w.text);
  }
  if (!flags.allow_overlap) RefuseOverlaps(scenario_, &source);

  const std::string name = fs::path(scenario_path_).stem().string();
  out_dir_ = fs::absolute(flags.out.empty() ? "out/" + name : flags.out)
                 .lexically_normal()
                 .string();
  fs::create_directories(out_dir_);
  // The summary must not read the end of an earlier run.
  checkpoint_ = out_dir_ + "/final.checkpoint";
  fs::remove(checkpoint_);

  RunOptions o = OptionsOf(scenario_, scenario_path_, flags);
  o.checkpoint_on_exit = checkpoint_;
  if (o.controller == ControllerKind::kLua) {
    // A file beside the outputs, as the studio writes one beside the design.
    if (!scenario_.run || scenario_.run->lua_script.empty()) {
      throw UsageError(flags.file +
                       ": <run> names a Lua controller but carries no "
                       "<luaScript>");
    }
    o.lua_script = out_dir_ + "/" + name + ".controller.lua";
    WriteFileAtomically(o.lua_script, scenario_.run->lua_script);
  }
  try {
    UseTunedGait(scenario_.run, flags.file + ": <run><tunedGait>",
                 out_dir_ + "/" + name + ".tuned.gait.xml", &o);
  } catch (const GaitFileError& e) {
    throw UsageError(e.what());
  }
  std::vector<ProcessSpec> specs = OutputSpecs(o, out_dir_, name);
  try {
    const std::vector<ProcessSpec> run = RunProcessSpecs(o);
    specs.insert(specs.end(), run.begin(), run.end());
  } catch (const std::invalid_argument& e) {
    throw UsageError(flags.file + ": " + e.what());
  }
  // The controllers, the logger and the viewer listen before the first
  // state (each has a ready line; RunLaunch starts the simulator after
  // them), so a lockstep or fast run is not over before the viewer has
  // set up its renderer.
  for (const std::string& left_out : flags.without) {
    const auto it =
        std::find_if(specs.begin(), specs.end(), [&](const ProcessSpec& p) {
          return p.name == left_out && !p.required;
        });
    if (it == specs.end()) {
      std::string names;
      for (const ProcessSpec& p : specs) {
        if (!p.required) names += (names.empty() ? "" : ", ") + p.name;
      }
      throw UsageError("--without " + left_out +
                       ": no such process to leave out (expected one of " +
                       names + ")");
    }
    specs.erase(it);
  }
  plan_.name = "run";
  const std::vector<std::string> search = ProgramSearchPath(argv0);
  for (ProcessSpec& spec : specs) {
    std::string path;
    try {
      path = FindProgram(spec.program, search);
    } catch (const std::runtime_error& e) {
      throw LaunchError(e.what());
    }
    plan_.processes.emplace_back(std::move(spec), path);
  }
}

int DesignRun::Run(const std::function<bool()>& stop, std::FILE* out) const {
  return RunLaunch(plan_, stop, out);
}

std::string DesignRun::Summary() const {
  const Physics start(scenario_);
  const std::unique_ptr<Physics> end = LoadCheckpoint(checkpoint_);
  return FormatRunSummary(SummarizeRun(start, *end));
}

}  // namespace mrsim
