#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <fstream>
#include <sstream>

#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/search/test_functions.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CountingEvaluator : BatchEvaluator {
  int evaluated = 0;
  int fail_after = -1;  // throw EvaluationInterrupted on this batch
  int batches = 0;
  std::vector<EvalResult> Evaluate(const std::vector<Genome>& batch) override {
    if (batches++ == fail_after) throw EvaluationInterrupted("stop");
    std::vector<EvalResult> r;
    for (const Genome& g : batch) {
      r.push_back(EvaluateTestFunction("rastrigin", g));
      ++evaluated;
    }
    return r;
  }
};

TEST(OptimizerRun, InterruptedRunResumesToTheSameResult) {
  const GenomeSpec spec = TestFunctionSpec(4, -5.12, 5.12, 2.0);
  AlgorithmSettings settings;
  settings.population = 8;
  settings.seed = 9;
  OptimizationRunOptions options;
  options.generations = 10;

  const std::string straight_dir = testing::TempDir("optimizer_run_straight");
  options.out_dir = straight_dir;
  CountingEvaluator straight_eval;
  const RunResult straight =
      RunOptimization(spec, settings, straight_eval, options);

  options.out_dir = testing::TempDir("optimizer_run_resumed");
  CountingEvaluator first;
  first.fail_after = 4;  // stops during the 5th generation
  EXPECT_THROW(RunOptimization(spec, settings, first, options),
               EvaluationInterrupted);
  CountingEvaluator second;
  const RunResult resumed = RunOptimization(spec, settings, second, options);
  EXPECT_EQ(resumed.generations_replayed, 4);
  EXPECT_EQ(resumed.best, straight.best);
  EXPECT_EQ(resumed.best_result.fitness, straight.best_result.fitness);
  // Nothing evaluated twice beyond the abandoned generation.
  EXPECT_EQ(first.evaluated + second.evaluated, straight_eval.evaluated + 0);
  for (const char* f :
       {"/generations.csv", "/evaluations.csv", "/checkpoint.txt"}) {
    EXPECT_EQ(ReadAll(options.out_dir + f), ReadAll(straight_dir + f)) << f;
  }
}

// Answers batches only when collected, oldest first, like a farm with
// several generations in flight; counts how many were in flight at once.
struct PipelinedEvaluator : CountingEvaluator {
  std::deque<std::vector<Genome>> in_flight;
  size_t most_in_flight = 0;
  void Submit(std::vector<Genome> batch) override {
    in_flight.push_back(std::move(batch));
    most_in_flight = std::max(most_in_flight, in_flight.size());
  }
  std::vector<EvalResult> Collect() override {
    std::vector<Genome> batch = std::move(in_flight.front());
    in_flight.pop_front();
    return Evaluate(batch);
  }
};

std::vector<std::vector<std::string>> CsvRows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(ReadAll(path));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream cell(line);
    for (std::string c; std::getline(cell, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

TEST(OptimizerRun,
     IslandsKeepTwoGenerationsInFlightAndIslandZeroIsTheSeedsRun) {
  const GenomeSpec spec = TestFunctionSpec(4, -5.12, 5.12, 2.0);
  AlgorithmSettings settings;
  settings.population = 6;
  settings.seed = 5;
  OptimizationRunOptions options;
  options.generations = 8;
  const std::string islands_dir = testing::TempDir("optimizer_run_islands");
  options.out_dir = islands_dir;
  settings.islands = 2;
  PipelinedEvaluator farm;
  const RunResult islands = RunOptimization(spec, settings, farm, options);
  EXPECT_EQ(farm.most_in_flight, 2u) << "the next island's generation waits";
  EXPECT_EQ(islands.generations_done, 8);

  const std::string plain_dir = testing::TempDir("optimizer_run_one_island");
  options.out_dir = plain_dir;
  options.generations = 4;
  settings.islands = 1;
  CountingEvaluator local;
  RunOptimization(spec, settings, local, options);
  // generations.csv: generation,best,mean,worst,best_so_far,failed,genes...
  const auto two = CsvRows(islands_dir + "/generations.csv");
  const auto one = CsvRows(plain_dir + "/generations.csv");
  ASSERT_EQ(two.size(), 9u);
  ASSERT_EQ(one.size(), 5u);
  for (size_t k = 1; k < one.size(); ++k) {
    const auto& even = two[2 * k - 1];  // island 0's generation k - 1
    for (size_t c : {1, 2, 3, 5}) EXPECT_EQ(even[c], one[k][c]) << k;
    EXPECT_EQ(std::vector<std::string>(even.begin() + 6, even.end() - 1),
              std::vector<std::string>(one[k].begin() + 6, one[k].end()));
  }
  // Each row names its island, last (a one-island file has no such column).
  EXPECT_EQ(two[0].back(), "island");
  for (size_t k = 1; k < two.size(); ++k) {
    EXPECT_EQ(two[k].back(), std::to_string((k - 1) % 2)) << k;
  }
  EXPECT_NE(one[0].back(), "island");
  // Fewer generations than islands would leave an island without any.
  settings.islands = 3;
  options.generations = 2;
  options.out_dir = testing::TempDir("optimizer_run_too_few");
  EXPECT_THROW(RunOptimization(spec, settings, local, options),
               std::invalid_argument);
  // Island 1 searches with a seed of its own: its generation 0 (after the
  // start genome, index 0) is not island 0's.
  const auto evals = CsvRows(islands_dir + "/evaluations.csv");
  ASSERT_GT(evals.size(), 8u);
  EXPECT_EQ(evals[2][0], "0");
  EXPECT_EQ(evals[8][0], "1");
  EXPECT_EQ(evals[2][1], evals[8][1]);
  EXPECT_NE(std::vector<std::string>(evals[2].begin() + 9, evals[2].end() - 1),
            std::vector<std::string>(evals[8].begin() + 9, evals[8].end() - 1));
}

TEST(OptimizerRun, AnInterruptedIslandRunResumesToTheSameFiles) {
  const GenomeSpec spec = TestFunctionSpec(4, -5.12, 5.12, 2.0);
  AlgorithmSettings settings;
  settings.population = 6;
  settings.seed = 3;
  settings.islands = 2;
  OptimizationRunOptions options;
  options.generations = 9;
  const std::string straight_dir = testing::TempDir("islands_straight");
  options.out_dir = straight_dir;
  PipelinedEvaluator straight;
  const RunResult whole = RunOptimization(spec, settings, straight, options);

  options.out_dir = testing::TempDir("islands_resumed");
  PipelinedEvaluator first;
  first.fail_after = 5;  // two generations submitted, five told
  EXPECT_THROW(RunOptimization(spec, settings, first, options),
               OptimizationInterrupted);
  PipelinedEvaluator second;
  const RunResult resumed = RunOptimization(spec, settings, second, options);
  EXPECT_EQ(resumed.generations_replayed, 5);
  EXPECT_EQ(resumed.best, whole.best);
  for (const char* f :
       {"/generations.csv", "/evaluations.csv", "/checkpoint.txt"}) {
    EXPECT_NE(ReadAll(straight_dir + f), "") << f;
    EXPECT_EQ(ReadAll(options.out_dir + f), ReadAll(straight_dir + f)) << f;
  }
  // Another number of islands is another run, and the refusal says so.
  for (int islands : {3, 1}) {
    settings.islands = islands;
    try {
      RunOptimization(spec, settings, second, options);
      ADD_FAILURE() << "resumed with " << islands << " islands";
    } catch (const CheckpointError& e) {
      EXPECT_NE(
          std::string(e.what()).find(islands == 3 ? "islands=2 (this run: 3)"
                                                  : "islands=2 (this run: 1)"),
          std::string::npos)
          << e.what();
    }
  }
  // One island's checkpoint names the islands a second run asks for.
  options.out_dir = testing::TempDir("islands_from_one");
  settings.islands = 1;
  RunOptimization(spec, settings, second, options);
  settings.islands = 2;
  try {
    RunOptimization(spec, settings, second, options);
    ADD_FAILURE() << "resumed one island's run with two";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("islands=1 (this run: 2)"),
              std::string::npos)
        << e.what();
  }
}

TEST(OptimizerRun, CheckpointOfOtherSettingsIsRefused) {
  const GenomeSpec spec = TestFunctionSpec(3, -1, 1, 0);
  AlgorithmSettings settings;
  settings.population = 4;
  OptimizationRunOptions options;
  options.generations = 2;
  options.out_dir = testing::TempDir("optimizer_run_refused");
  CountingEvaluator e;
  RunOptimization(spec, settings, e, options);
  settings.seed = 2;
  settings.population = 6;
  try {
    RunOptimization(spec, settings, e, options);
    FAIL() << "a checkpoint of other settings was continued";
  } catch (const CheckpointError& err) {
    // It says which settings changed.
    EXPECT_NE(
        std::string(err.what())
            .find("other settings: population=4 (this run: 6), seed=1 (this "
                  "run: 2)"),
        std::string::npos)
        << err.what();
  }
  // Same settings, other gene limits: the gene is named.
  settings.seed = 1;
  settings.population = 4;
  try {
    RunOptimization(TestFunctionSpec(3, -2, 2, 0), settings, e, options);
    FAIL() << "a checkpoint of another genome was continued";
  } catch (const CheckpointError& err) {
    EXPECT_NE(std::string(err.what()).find("=-1:1:0:on (this run: -2:2:0:on)"),
              std::string::npos)
        << err.what();
  }
  // Episode settings the caller describes are named too.
  options.out_dir = testing::TempDir("optimizer_run_refused_episode");
  options.fingerprint = "episode 1 s";
  options.described = "episode=1\n";
  RunOptimization(spec, settings, e, options);
  options.fingerprint = "episode 2 s";
  options.described = "episode=2\n";
  try {
    RunOptimization(spec, settings, e, options);
    FAIL() << "a checkpoint of other episodes was continued";
  } catch (const CheckpointError& err) {
    EXPECT_NE(
        std::string(err.what()).find("other settings: episode=1 (this run: 2)"),
        std::string::npos)
        << err.what();
  }
  // What no line describes is said as such.
  options.fingerprint = "another scenario";
  options.described = "episode=1\n";
  try {
    RunOptimization(spec, settings, e, options);
    FAIL() << "a checkpoint of another scenario was continued";
  } catch (const CheckpointError& err) {
    EXPECT_NE(std::string(err.what())
                  .find("another scenario, genome or episode settings"),
              std::string::npos)
        << err.what();
  }
}

TEST(OptimizerRun, JumpToReplaysWithoutTouchingTheFiles) {
  const GenomeSpec spec = TestFunctionSpec(3, -5, 5, 4);
  AlgorithmSettings settings;
  settings.population = 6;
  OptimizationRunOptions options;
  options.generations = 8;
  options.out_dir = testing::TempDir("optimizer_run_jump");
  CountingEvaluator e;
  RunOptimization(spec, settings, e, options);
  const std::string before = ReadAll(options.out_dir + "/evaluations.csv");
  options.stop_after = 3;
  CountingEvaluator none;
  const RunResult jump = RunOptimization(spec, settings, none, options);
  EXPECT_EQ(none.evaluated, 0);
  EXPECT_EQ(jump.generations_done, 3);
  EXPECT_FALSE(jump.wrote_files);
  EXPECT_LE(jump.best_generation, 2);
  EXPECT_EQ(before, ReadAll(options.out_dir + "/evaluations.csv"));
  // Generation 0 is no generation (it once crashed writing a best).
  options.stop_after = 0;
  EXPECT_THROW(RunOptimization(spec, settings, none, options),
               std::invalid_argument);
}

}  // namespace
}  // namespace mrsim
