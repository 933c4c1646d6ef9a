#include "optimizer/episode/task_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_presets.h"
#include "optimizer/episode/task.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {

const std::vector<std::string>& TableGaits() {
  // The forward wave and the classic gaits, with the CPG versions there
  // are; the domain table's turning and sidewinding variants are left out
  // (they are the forward wave and sidewinding again, turned).
  static const std::vector<std::string> kGaits = {
      "task",         "forward",       "cpg-forward",
      "serpenoid",    "cpg-serpenoid", "concertina",
      "helical-pipe", "sidewind",      "conical-sidewind"};
  return kGaits;
}

std::string TaskListMarkdown() {
  std::string text =
      "| task | world | fitness (m) | episode |\n|---|---|---|---|\n";
  for (const std::string& name : TaskNames()) {
    const Task t = MakeTask(name);
    text += fmt::format("| {} | {} | {} | {:g} s |\n", t.name, t.world,
                        TaskFitnessText(t), t.duration);
  }
  return text;
}

namespace {

std::string Cell(const EvalResult& r) {
  if (r.failed) return "unstable";
  // No "-0.000": a value that rounds to zero is zero.
  const double v = std::abs(r.distance) < 0.0005 ? 0.0 : r.distance;
  return fmt::format("{:.3f}", v);
}

}  // namespace

std::string PresetResultsMarkdown(int workers) {
  const std::vector<std::string>& names = TaskNames();
  const std::vector<std::string>& gaits = TableGaits();
  std::vector<Task> tasks;
  for (const std::string& n : names) tasks.push_back(MakeTask(n));
  std::vector<std::string> cells(gaits.size() * tasks.size());
  std::atomic<size_t> next{0};
  const auto work = [&] {
    for (size_t i = next++; i < cells.size(); i = next++) {
      const Task& t = tasks[i % tasks.size()];
      const std::string& g = gaits[i / tasks.size()];
      cells[i] =
          Cell(EvaluateTask(t, g == "task" ? t.gait : *FindGaitPreset(g)));
    }
  };
  const int n =
      workers > 0
          ? workers
          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> threads;
  for (int k = 0; k < n; ++k) threads.emplace_back(work);
  for (std::thread& th : threads) th.join();

  std::string text = "| gait |";
  std::string rule = "|---|";
  for (const std::string& n : names) {
    text += fmt::format(" {} |", n);
    rule += "---|";
  }
  text += "\n" + rule + "\n";
  for (size_t g = 0; g < gaits.size(); ++g) {
    text += fmt::format("| `{}` |", gaits[g]);
    for (size_t k = 0; k < tasks.size(); ++k) {
      text += fmt::format(" {} |", cells[g * tasks.size() + k]);
    }
    text += "\n";
  }
  return text;
}

std::string TaskListText() {
  std::string text = fmt::format("{:<8} {:<8} {:>5}  {:<14} {}\n", "task",
                                 "fitness", "s", "gait", "world");
  for (const std::string& n : TaskNames()) {
    const Task t = MakeTask(n);
    text +=
        fmt::format("{:<8} {:<8} {:>5g}  {:<14} {}\n", t.name, t.distance_mode,
                    t.duration, t.gait.name, t.description);
  }
  return text;
}

std::string TasksMarkdown(int workers) {
  return TaskListMarkdown() + "\n" + PresetResultsMarkdown(workers);
}

std::string RunTaskCommand(const TaskCommand& c) {
  if (c.markdown) return TasksMarkdown();
  if (c.task.empty()) return TaskListText();
  const Task t = MakeTask(c.task);
  if (!c.gait.empty()) {
    const EvalResult r = EvaluateTask(
        t, c.gait == "task" ? t.gait : ResolveGait(c.gait), c.seconds);
    return fmt::format("{} {} {}: {:.3f} m{}\n", t.name, c.gait,
                       t.distance_mode, r.distance,
                       r.failed ? " (unstable)" : "");
  }
  if (c.write.empty()) {
    return fmt::format(
        "{}: {}\nfitness: {} (m), episode {} s, suggested gait {}\n", t.name,
        t.description, t.distance_mode, t.duration, t.gait.name);
  }
  WriteScenarioFile(t.scenario, c.write);
  return fmt::format("wrote {}\n", c.write);
}

}  // namespace mrsim
