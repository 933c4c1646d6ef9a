#include "optimizer/process/opt_command.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "optimizer/farm/farm_master_core.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

OptCommand Parse(std::vector<std::string> args) {
  CLI::App app;
  OptCommand command;
  AddOptFlags(app, command);
  std::reverse(args.begin(), args.end());  // CLI11 takes them reversed
  app.parse(args);
  return command;
}

std::vector<std::string> SnakeArgs(const std::string& out) {
  return {testing::SourcePath("scenarios/snake11.xml"), "--genome",
          testing::SourcePath("scenarios/forward_gait.genome.xml"), "--out",
          out};
}

std::vector<std::string> With(std::vector<std::string> a,
                              const std::vector<std::string>& more) {
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// Everything a FILE* received, as text.
std::string Contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  return text;
}

TEST(OptCommand, FlagsFillTheCommand) {
  const OptCommand c = Parse(
      With(SnakeArgs("out"),
           {"--algorithm", "cmaes", "--cmaes-sigma", "0.2", "--population", "6",
            "--episode", "3", "--seed", "7", "--w-energy", "0.5", "--farm",
            "--chunk-size", "1000", "--no-start-genome", "--jump-to", "4"}));
  EXPECT_EQ(c.algorithm.algorithm, AlgorithmKind::kCmaes);
  EXPECT_EQ(c.algorithm.cmaes_sigma, 0.2);
  EXPECT_EQ(c.algorithm.population, 6);
  EXPECT_EQ(c.algorithm.seed, 7u);
  EXPECT_EQ(c.episode.duration, 3.0);
  EXPECT_EQ(c.episode.fitness.w_energy, 0.5);
  EXPECT_TRUE(c.farm);
  EXPECT_EQ(c.chunk_size, 1000);
  EXPECT_TRUE(c.no_start);
  EXPECT_EQ(c.jump_to, 4);
  EXPECT_EQ(c.out_dir, "out");
}

TEST(OptCommand, RobustFlagsAskForKPerturbedEpisodes) {
  const OptCommand c = Parse(
      With(SnakeArgs("out"), {"--robust", "8", "--robust-mode", "worst"}));
  EXPECT_EQ(c.episode.robust.episodes, 8);
  EXPECT_EQ(c.episode.robust.mode, "worst");
  EXPECT_EQ(Parse(SnakeArgs("out")).episode.robust.episodes, 0);
}

// Under loss a chunk of many IP fragments is lost whole whenever one of
// them is: without --chunk-size the farm sends one-frame chunks.
TEST(OptCommand, FarmPayloadChunksFitOneFrameUnlessAsked) {
  EXPECT_EQ(Parse(With(SnakeArgs("out"), {"--farm"})).chunk_size, 0);
  FarmMasterCore master(std::string(100000, 'x'), "run", 1, FarmSettings{});
  EXPECT_GT(master.chunk_count(), 70);  // ~1,370 bytes each
}

TEST(OptCommand, BadInputIsAnInputErrorNamingTheProblem) {
  const std::string out = testing::TempDir("opt_command_bad");
  auto message = [&](const std::vector<std::string>& more,
                     std::vector<std::string> base = {}) {
    if (base.empty()) base = SnakeArgs(out);
    try {
      PrepareOpt(Parse(With(base, more)));
    } catch (const OptInputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"--workers", "remote:3"}).find("--workers"),
            std::string::npos);
  EXPECT_NE(message({"--workers", "local:x"}).find("local:K"),
            std::string::npos);
  EXPECT_NE(message({"--generations", "0"}).find("--generations"),
            std::string::npos);
  EXPECT_NE(
      message({"--algorithm", "cmaes", "--population", "1"}).find("CMA-ES"),
      std::string::npos);
  // A word no algorithm has is a usage error while parsing, naming the
  // flag and every algorithm of the registry.
  try {
    Parse(With(SnakeArgs(out), {"--algorithm", "nope"}));
    ADD_FAILURE() << "--algorithm nope accepted";
  } catch (const CLI::ValidationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--algorithm"), std::string::npos) << what;
    EXPECT_NE(what.find("nope"), std::string::npos) << what;
    for (const AlgorithmInfo& info : Algorithms()) {
      EXPECT_NE(what.find(info.name), std::string::npos) << what;
    }
  }
  // Farm settings out of range, or one the farm would ignore.
  EXPECT_NE(message({"--farm", "--chunk-size", "70000"})
                .find("--chunk-size: expected 0 (one Ethernet frame) or "
                      "1..60000, got 70000"),
            std::string::npos);
  EXPECT_NE(
      message({"--farm", "--worker-timeout", "-1"}).find("--worker-timeout"),
      std::string::npos);
  EXPECT_NE(message({"--farm", "--workers", "local:2"})
                .find("mrsim-worker --threads"),
            std::string::npos);
  // --jump-to counts from 1 and stays within the run (0 once crashed).
  EXPECT_NE(message({"--generations", "3", "--jump-to", "4"})
                .find("--jump-to 4: beyond the run's --generations 3"),
            std::string::npos);
  for (const char* bad : {"0", "-3"}) {
    EXPECT_THROW(Parse(With(SnakeArgs(out), {"--jump-to", bad})),
                 CLI::ValidationError)
        << bad;
  }
  // Islands: each needs a generation; the range is CLI11's.
  EXPECT_NE(message({"--generations", "2", "--islands", "3"})
                .find("--generations 2 with --islands 3"),
            std::string::npos);
  for (const char* bad : {"0", "17"}) {
    EXPECT_THROW(Parse(With(SnakeArgs(out), {"--islands", bad})),
                 CLI::ValidationError)
        << bad;
  }
  const std::string bad_genome = out + "/bad.genome.xml";
  std::ofstream(bad_genome)
      << "<genome><gene name=\"T\" lower=\"1\"/></genome>";
  EXPECT_NE(message({}, {testing::SourcePath("scenarios/snake11.xml"),
                         "--genome", bad_genome, "--out", out})
                .find("bad.genome.xml"),
            std::string::npos);
}

// Stops after `batches` batches, as Ctrl-C does.
class StoppingEvaluator : public BatchEvaluator {
 public:
  StoppingEvaluator(BatchEvaluator& inner, int batches)
      : inner_(inner), left_(batches) {}
  std::vector<EvalResult> Evaluate(const std::vector<Genome>& batch) override {
    if (left_-- == 0) throw EvaluationInterrupted("stopped");
    return inner_.Evaluate(batch);
  }

 private:
  BatchEvaluator& inner_;
  int left_;
};

// Two runs on one --out would write the same checkpoint temporary file:
// the second is refused, naming the process that holds the folder, and a
// lock its holder left behind when killed is taken over.
// A body genome starting from a body that overlaps the scene (the case
// study's ball put in module 0) is refused before any episode, naming the
// parts as mrsim-sim does; so is a gait-only genome on that file (its
// episodes would score the physics pushing the ball out as distance),
// unless the user allows overlap as mrsim-sim's flag does.
TEST(OptCommand, AStartBodyOverlappingTheSceneIsRefusedNamingItsParts) {
  const std::string dir = testing::TempDir("opt_command_overlap");
  Scenario s =
      ReadScenarioFile(testing::SourcePath("scenarios/case_study.xml"));
  s.scene_objects.at(0).position = s.robots.at(0).modules.at(0).position;
  const std::string scenario = dir + "/ball_in_the_robot.xml";
  WriteScenarioFile(s, scenario);
  const std::string genome = dir + "/body.genome.xml";
  std::ofstream(genome) << R"(<genome>
  <gene name="module_scale" lower="0.5" upper="2" start="1"/>
</genome>)";
  try {
    PrepareOpt(Parse({scenario, "--genome", genome, "--out", dir + "/out"}));
    ADD_FAILURE() << "an overlapping start body was accepted";
  } catch (const OptInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene object 'ball' by "), std::string::npos) << what;
    EXPECT_NE(what.find("body genes' start values"), std::string::npos) << what;
  }
  const std::string gait = dir + "/gait.genome.xml";
  std::ofstream(gait) << R"(<genome>
  <gene name="A_pitch" lower="0" upper="1.5" start="1"/>
</genome>)";
  try {
    PrepareOpt(Parse({scenario, "--genome", gait, "--out", dir + "/gait"}));
    ADD_FAILURE() << "an overlapping file was optimised with gait genes";
  } catch (const OptInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene object 'ball' by "), std::string::npos) << what;
    EXPECT_NE(what.find("--allow-overlap"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(PrepareOpt(Parse({scenario, "--genome", gait, "--out",
                                    dir + "/allowed", "--allow-overlap"})));
}

TEST(OptCommand, ARunFolderIsLockedWhileARunWritesIt) {
  const std::string out = testing::TempDir("opt_command_lock");
  const OptCommand c = Parse(SnakeArgs(out));
  {
    const OptSetup first = PrepareOpt(c);
    try {
      PrepareOpt(c);
      FAIL() << "two runs on one folder";
    } catch (const OptInputError& e) {
      EXPECT_NE(std::string(e.what()).find("another mrsim-opt (process " +
                                           std::to_string(getpid()) +
                                           ") is writing this run folder"),
                std::string::npos)
          << e.what();
    }
  }
  std::FILE* stale = std::fopen((out + "/.mrsim-opt.lock").c_str(), "w");
  ASSERT_NE(stale, nullptr);
  std::fputs("4242\n", stale);
  std::fclose(stale);
  const OptSetup after = PrepareOpt(c);
  EXPECT_EQ(after.lock->stale_holder(), 4242);
}

TEST(OptCommand, AStopSaysWhetherThereIsAnythingToContinueFrom) {
  for (int batches : {0, 2}) {
    const std::string out =
        testing::TempDir("opt_command_stop") + "/" + std::to_string(batches);
    const OptCommand c = Parse(
        With(SnakeArgs(out), {"--population", "3", "--generations", "4",
                              "--episode", "0.2", "--workers", "local:1"}));
    const OptSetup setup = PrepareOpt(c);
    auto evaluator = MakeOptEvaluator(c, setup, nullptr, nullptr);
    StoppingEvaluator stopping(*evaluator, batches);
    std::FILE* text = std::tmpfile();
    std::FILE* notes = std::tmpfile();
    EXPECT_TRUE(RunOpt(c, setup, stopping, text, notes).stopped);
    const std::string said = Contents(notes);
    if (batches == 0) {
      EXPECT_NE(said.find("stopped before the first generation completed"),
                std::string::npos)
          << said;
      EXPECT_FALSE(fs::exists(out + "/checkpoint.txt"));
    } else {
      EXPECT_NE(said.find("run the same command to continue"),
                std::string::npos)
          << said;
      EXPECT_TRUE(fs::exists(out + "/checkpoint.txt"));
    }
    std::fclose(text);
    std::fclose(notes);
  }
}

TEST(OptCommand, RunWritesTheBestAndAProgressLinePerGeneration) {
  const std::string out = testing::TempDir("opt_command_run");
  const OptCommand c =
      Parse(With(SnakeArgs(out),
                 {"--algorithm", "cmaes", "--population", "3", "--generations",
                  "2", "--episode", "0.5", "--workers", "local:1"}));
  const OptSetup setup = PrepareOpt(c);
  auto evaluator = MakeOptEvaluator(c, setup, nullptr, nullptr);
  std::FILE* text = std::tmpfile();
  std::FILE* notes = std::tmpfile();
  const OptOutcome outcome = RunOpt(c, setup, *evaluator, text, notes);
  EXPECT_FALSE(outcome.stopped);
  EXPECT_EQ(outcome.best_dir, out);
  for (const char* f : {"best_gait.xml", "best_scenario.xml", "best_genome.xml",
                        "replay.launch", "checkpoint.txt"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  const std::string printed = Contents(text);
  EXPECT_NE(printed.find("generation 1 of 2: best"), std::string::npos)
      << printed;
  EXPECT_NE(printed.find("generation 2 of 2: best"), std::string::npos);
  EXPECT_NE(printed.find("best fitness"), std::string::npos);
  std::fclose(text);
  std::fclose(notes);

  // A jump into the finished run replays it and writes the best apart.
  OptCommand jump = c;
  jump.jump_to = 1;
  jump.quiet = true;
  std::FILE* quiet = std::tmpfile();
  const OptOutcome older = RunOpt(jump, setup, *evaluator, quiet, quiet);
  EXPECT_EQ(older.best_dir, out + "/jump-1");
  EXPECT_TRUE(fs::exists(out + "/jump-1/best_gait.xml"));
  const std::string quiet_text = Contents(quiet);
  EXPECT_EQ(quiet_text.find(": best "), std::string::npos) << quiet_text;
  // The summary counts as the progress lines do, and names the CSV row.
  EXPECT_NE(quiet_text.find("in generation 1 of 1 (generation 0, index "),
            std::string::npos)
      << quiet_text;
  std::fclose(quiet);
}

TEST(OptCommand, SlurmFlagsNeedTheFarmAndAMatchingHubUrl) {
  const std::string out = testing::TempDir("opt_command_slurm");
  const OptCommand c =
      Parse(With(SnakeArgs(out),
                 {"--farm", "--slurm", "4", "--slurm-opt", "partition=debug",
                  "--slurm-opt=--time=10", "--hub", "7701"}));
  EXPECT_EQ(c.slurm, 4);
  EXPECT_EQ(c.slurm_options,
            (std::vector<std::string>{"partition=debug", "--time=10"}));
  EXPECT_EQ(c.hub_port, 7701);
  auto message = [&](const std::vector<std::string>& more) {
    try {
      PrepareOpt(Parse(With(SnakeArgs(out), more)));
    } catch (const OptInputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"--slurm", "2"}).find("add --farm"), std::string::npos);
  EXPECT_NE(message({"--farm", "--slurm-opt", "time=1"}).find("--slurm N"),
            std::string::npos);
  EXPECT_NE(message({"--farm", "--slurm", "2", "--slurm-opt", "array=1-3"})
                .find("sets --array itself"),
            std::string::npos);
  EXPECT_NE(message({"--farm", "--hub", "7701", "--lcm-url",
                     "udpm://239.255.76.67:7667"})
                .find("tcpq://HOST:7701"),
            std::string::npos);
  EXPECT_EQ(message({"--farm", "--hub", "7701", "--lcm-url",
                     "tcpq://127.0.0.1:7701"}),
            "no error");
}

TEST(OptCommand, FarmOnAnUnusableLcmUrlIsRefused) {
  OptCommand c = Parse(With(SnakeArgs(testing::TempDir("opt_command_farm")),
                            {"--farm", "--lcm-url", "nonsense://nowhere"}));
  const OptSetup setup = PrepareOpt(c);
  EXPECT_THROW(MakeOptEvaluator(c, setup, nullptr, nullptr),
               std::runtime_error);
}

TEST(OptCommand, ProgressAndDurationsReadWell) {
  EXPECT_EQ(FormatDuration(42), "42s");
  EXPECT_EQ(FormatDuration(75), "1m15s");
  EXPECT_EQ(FormatDuration(3700), "1h01m");
  EXPECT_EQ(FormatDuration(-1), "?");
  GenerationReport r;
  r.generation = 3;
  r.generations = 20;
  r.best = 0.41;
  r.mean = 0.2;
  r.best_so_far = 0.45;
  r.evals_per_second = 5.2;
  r.workers = 2;
  r.eta_seconds = 72;
  EXPECT_EQ(FormatProgress(r),
            "generation 3 of 20: best 0.41 mean 0.2 best-so-far 0.45 | 5.20 "
            "evals/s | workers 2 | ETA 1m12s");
  // Failed individuals pull the mean down: the line says how many.
  r.failed = 2;
  EXPECT_NE(FormatProgress(r).find("best-so-far 0.45 failed 2 | "),
            std::string::npos)
      << FormatProgress(r);
  // ... and why, each reason once, not a line per individual.
  r.failed_reasons = {
      {"overlap at the start: robot 'snake' module 13 front "
       "frame / scene object 'ball'",
       2}};
  EXPECT_NE(FormatProgress(r).find(
                "best-so-far 0.45 failed 2 (overlap at the start: robot "
                "'snake' module 13 front frame / scene object 'ball') | "),
            std::string::npos)
      << FormatProgress(r);
  r.failed_reasons = {};
  r.replayed = true;
  r.eta_seconds = -1;  // only replayed so far: no pace yet
  EXPECT_NE(FormatProgress(r).find("from checkpoint"), std::string::npos);
  EXPECT_NE(FormatProgress(r).find("ETA ?"), std::string::npos);
  // With islands each line says whose generation it was: the bests of two
  // searches alternate.
  r.island = 1;
  EXPECT_EQ(FormatProgress(r).rfind("generation 3 of 20 (island 1): best", 0),
            0u)
      << FormatProgress(r);
}

// Failed individuals by reason: one reason alone, the two most frequent
// with their counts, the rest summed; failures that gave none say nothing
// more than their count.
TEST(OptCommand, FailedIndividualsAreCountedByReason) {
  EXPECT_EQ(FormatFailedReasons({}), "");
  EXPECT_EQ(FormatFailedReasons({{"", 3}}), "");
  EXPECT_EQ(FormatFailedReasons({{"the simulation became unstable", 3}}),
            "the simulation became unstable");
  EXPECT_EQ(FormatFailedReasons({{"overlap at the start: a / b", 3}, {"", 1}}),
            "3 overlap at the start: a / b; 1 no reason given");
  EXPECT_EQ(FormatFailedReasons({{"overlap at the start: a / b", 5},
                                 {"the simulation became unstable", 2},
                                 {"gait values refused: T", 1},
                                 {"body refused: x", 1}}),
            "5 overlap at the start: a / b; 2 the simulation became "
            "unstable; 2 for 2 other reasons");
}

}  // namespace
}  // namespace mrsim
