// mrsim-tasks (`mrsim tasks`): lists the task suite (docs/tasks.md), or
// writes one task's scenario to a file for mrsim-sim, the studio or a
// launch file.
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "common/cli_exit.h"
#include "gait_controller/gait_file.h"
#include "lcmtypes/runtime/version.h"
#include "optimizer/task.h"
#include "sim_core/scenario_xml.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-tasks: the task suite (docs/tasks.md)"};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-tasks"));
  std::string name;
  std::string out;
  app.add_option("task", name, "Task to describe or write");
  std::string gait;
  double seconds = 0;
  app.add_option("--write", out, "Write the task's scenario to this file")
      ->needs(app.get_option("task"));
  app.add_option("--gait", gait,
                 "Run one episode of this gait (preset or "
                 "file) and print its fitness")
      ->needs(app.get_option("task"));
  app.add_option("--seconds", seconds, "Episode length (default: the task's)")
      ->check(CLI::PositiveNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    return mrsim::CliParseExit(app, err);
  }
  try {
    if (name.empty()) {
      fmt::print("{:<8} {:<8} {:>5}  {:<14} {}\n", "task", "fitness", "s",
                 "gait", "world");
      for (const std::string& n : mrsim::TaskNames()) {
        const mrsim::Task t = mrsim::MakeTask(n);
        fmt::print("{:<8} {:<8} {:>5g}  {:<14} {}\n", t.name, t.distance_mode,
                   t.duration, t.gait.name, t.description);
      }
      return 0;
    }
    const mrsim::Task t = mrsim::MakeTask(name);
    if (!gait.empty()) {
      const mrsim::EvalResult r = mrsim::EvaluateTask(
          t, gait == "task" ? t.gait : mrsim::ResolveGait(gait), seconds);
      fmt::print("{} {} {}: {:.3f} m{}\n", t.name, gait, t.distance_mode,
                 r.distance, r.failed ? " (unstable)" : "");
      return 0;
    }
    if (out.empty()) {
      fmt::print("{}: {}\nfitness: {} (m), episode {} s, suggested gait {}\n",
                 t.name, t.description, t.distance_mode, t.duration,
                 t.gait.name);
      return 0;
    }
    mrsim::WriteScenarioFile(t.scenario, out);
    fmt::print("wrote {}\n", out);
    return 0;
  } catch (const mrsim::GaitFileError& err) {
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 2;
  } catch (const mrsim::TaskError& err) {
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 2;
  } catch (const std::exception& err) {
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 1;
  }
}
