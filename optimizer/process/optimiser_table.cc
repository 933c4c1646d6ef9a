#include "optimizer/process/optimiser_table.h"

#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "optimizer/process/opt_command.h"
#include "optimizer/episode/task.h"

namespace mrsim {

namespace fs = std::filesystem;

const std::vector<OptimiserTableRow>& OptimiserTableRows() {
  static const std::vector<OptimiserTableRow> kRows = {
      {"CMA-ES, `--genes sine`", {"--genes", "sine"}},
      {"CMA-ES, `--genes cpg`", {"--genes", "cpg"}},
      {"CMA-ES, `--controller lua:examples/optimise/serpenoid_params.lua`",
       {"--controller", "lua:examples/optimise/serpenoid_params.lua"}},
      {"CMA-ES, `--controller mlp:8`", {"--controller", "mlp:8"}},
  };
  return kRows;
}

std::vector<std::string> OptimiserCellArguments(const std::string& task,
                                                const OptimiserTableRow& row,
                                                const std::string& out_dir) {
  std::vector<std::string> args = {"--task", task};
  args.insert(args.end(), row.flags.begin(), row.flags.end());
  const std::vector<std::string> rest = {
      "--algorithm",   "cmaes",
      "--population",  "8",
      "--generations", "3",
      "--seed",        "1",
      "--episode",     fmt::format("{:g}", MakeTask(task).duration),
      "--workers",     "local:1",
      "--out",         out_dir};
  args.insert(args.end(), rest.begin(), rest.end());
  return args;
}

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};

std::string Cell(double v) {
  if (!std::isfinite(v)) return "unstable";
  // No "-0.000": a value that rounds to zero is zero.
  return fmt::format("{:.3f}", std::abs(v) < 0.0005 ? 0.0 : v);
}

}  // namespace

double RunOptimiserCell(const std::string& task, const OptimiserTableRow& row,
                        const std::string& scratch_dir) {
  std::string label = task;
  for (const std::string& f : row.flags) label += "-" + f;
  for (char& ch : label) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '-';
  }
  const std::string out = scratch_dir + "/" + label;
  // A leftover checkpoint would be resumed: start from nothing.
  fs::remove_all(out);
  std::vector<std::string> args = OptimiserCellArguments(task, row, out);
  args.push_back("--quiet");
  // The very flags mrsim-opt parses, so a cell is its command line.
  OptCommand command;
  CLI::App app{"mrsim-opt"};
  AddOptFlags(app, command);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  app.parse(reversed);
  double best = 0;
  {
    const OptSetup setup = PrepareOpt(command);
    auto evaluator = MakeOptEvaluator(command, setup, [] { return false; }, {});
    std::unique_ptr<std::FILE, FileCloser> sink(std::tmpfile());
    if (!sink) throw std::runtime_error("cannot open a temporary file");
    const OptOutcome outcome =
        RunOpt(command, setup, *evaluator, sink.get(), sink.get());
    const EvalResult& b = outcome.result.best_result;
    best = b.failed ? std::nan("") : b.fitness;
  }
  fs::remove_all(out);
  return best;
}

std::string OptimiserResultsMarkdown(
    int jobs, const std::function<void(const std::string&)>& progress) {
  const std::vector<std::string>& tasks = TaskNames();
  const std::vector<OptimiserTableRow>& rows = OptimiserTableRows();
  const size_t total = rows.size() * tasks.size();
  const std::string scratch =
      (fs::temp_directory_path() /
       fmt::format("mrsim-tasks-optimisers-{}", ::getpid()))
          .string();
  fs::create_directories(scratch);
  std::vector<std::string> cells(total);
  std::atomic<size_t> next{0};
  std::mutex mutex;
  size_t done = 0;
  std::exception_ptr error;
  const auto start = std::chrono::steady_clock::now();
  const auto work = [&] {
    for (size_t i = next++; i < total; i = next++) {
      const size_t r = i / tasks.size();
      const std::string& task = tasks[i % tasks.size()];
      try {
        cells[i] = Cell(RunOptimiserCell(task, rows[r], scratch));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        next = total;  // the others stop after their cell
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) {
        const double elapsed = std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
        progress(fmt::format(
            "cell {} of {} done: row {} of {} ({}), {}: {}; ETA {}", done,
            total, r + 1, rows.size(), rows[r].label, task, cells[i],
            FormatDuration(elapsed / done * (total - done))));
      }
    }
  };
  const int n =
      jobs > 0
          ? jobs
          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> threads;
  for (int k = 0; k < n; ++k) threads.emplace_back(work);
  for (std::thread& th : threads) th.join();
  std::error_code ec;
  fs::remove_all(scratch, ec);
  if (error) std::rethrow_exception(error);

  std::string text = "| optimiser |";
  std::string rule = "|---|";
  for (const std::string& t : tasks) {
    text += fmt::format(" {} |", t);
    rule += "---|";
  }
  text += "\n" + rule + "\n";
  for (size_t r = 0; r < rows.size(); ++r) {
    text += fmt::format("| {} |", rows[r].label);
    for (size_t k = 0; k < tasks.size(); ++k) {
      text += fmt::format(" {} |", cells[r * tasks.size() + k]);
    }
    text += "\n";
  }
  return text;
}

}  // namespace mrsim
