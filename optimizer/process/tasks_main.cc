// mrsim-tasks (`mrsim tasks`): lists the task suite (docs/tasks.md), prints
// its tables, runs one episode of a gait on a task, or writes one task's
// scenario to a file for mrsim-sim, the studio or a launch file.
#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "common/cli_exit.h"
#include "gait_controller/gait_file.h"
#include "lcmtypes/runtime/version.h"
#include "optimizer/process/opt_command.h"
#include "optimizer/process/optimiser_table.h"
#include "optimizer/episode/task.h"
#include "optimizer/episode/task_table.h"

int main(int argc, char** argv) {
  CLI::App app{"mrsim-tasks: the task suite (docs/tasks.md)"};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-tasks"));
  mrsim::TaskCommand c;
  auto* task = app.add_option("task", c.task, "Task to describe or write");
  app.add_option("--write", c.write, "Write the task's scenario to this file")
      ->needs(task);
  app.add_option("--gait", c.gait,
                 "Run one episode of this gait (preset, file or 'task': the "
                 "task's own) and print its fitness")
      ->needs(task);
  app.add_option("--seconds", c.seconds, "Episode length (default: the task's)")
      ->check(CLI::PositiveNumber);
  auto* markdown =
      app.add_flag("--markdown", c.markdown,
                   "Print the tables of docs/tasks.md: the tasks and every "
                   "compared gait's fitness on each (a minute or two)")
          ->excludes(task);
  bool optimisers = false;
  int jobs = 0;
  app.add_flag("--optimisers", optimisers,
               "With --markdown: the optimiser table too, every row's "
               "mrsim-opt run on every task (long: progress on stderr)")
      ->needs(markdown);
  app.add_option("-j,--jobs", jobs,
                 "Optimiser cells run at once (0: one per core; each is "
                 "one single-threaded run, so the table is the same)")
      ->check(CLI::NonNegativeNumber);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    return mrsim::CliParseExit(app, err);
  }
  try {
    fmt::print("{}", mrsim::RunTaskCommand(c));
    if (c.markdown && optimisers) {
      std::fflush(stdout);
      fmt::print("\n{}", mrsim::OptimiserResultsMarkdown(jobs, [](auto& l) {
                   fmt::print(stderr, "mrsim-tasks: {}\n", l);
                 }));
    }
    return 0;
  } catch (const mrsim::GaitFileError& err) {
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 2;
  } catch (const mrsim::TaskError& err) {
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 2;
  } catch (const mrsim::OptInputError& err) {  // e.g. the Lua row's script
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 2;
  } catch (const std::exception& err) {
    fmt::print(stderr, "mrsim-tasks: {}\n", err.what());
    return 1;
  }
}
