// The tables of docs/tasks.md made from the task suite itself, so the docs
// cannot drift from the code (`mrsim tasks --markdown`; a test checks that
// docs/tasks.md holds them), and the rest of what `mrsim tasks` prints.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

// The gaits of the results table, in its order: "task" (each task's own
// gait), then the presets compared on every task.
const std::vector<std::string>& TableGaits();

// The task list: | task | world | fitness (m) | episode |, one row a task.
std::string TaskListMarkdown();

// The results: one row per TableGaits() entry, one column per task, the
// fitness of one episode of the task's length to 3 decimals ("unstable"
// when the simulation failed). Every episode is deterministic, so the
// table is the same bit for bit whatever `workers` (threads; 0: one per
// core).
std::string PresetResultsMarkdown(int workers = 0);

// `mrsim tasks` without a task: one line a task (name, fitness, episode,
// gait, description).
std::string TaskListText();

// The task list and the results table, a blank line between them: what
// docs/tasks.md shows.
std::string TasksMarkdown(int workers = 0);

// The flags of mrsim-tasks.
struct TaskCommand {
  std::string task;    // "": every task
  std::string write;   // write the task's scenario to this file
  std::string gait;    // run one episode of it ("task": the task's own)
  double seconds = 0;  // the episode (0: the task's)
  bool markdown = false;
};

// What mrsim-tasks prints for `c`: the list, the tables, one task, one
// episode's fitness, or the file written. Throws TaskError for an unknown
// task, GaitFileError for a gait it cannot read, and whatever writing the
// scenario throws.
std::string RunTaskCommand(const TaskCommand& c);

}  // namespace mrsim
