// The studio's Optimise: the mrsim-opt command line, reading its progress,
// and a real 2-generation run started the way the window starts it.
#include "studio/live/optimise_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "studio/live/best_replay.h"
#include "studio/live/live_link.h"
#include "studio/live/live_runner.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

using testing::BinaryPath;
using testing::SourcePath;
using testing::TempDir;

bool Has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

std::string Console(const OptimiseSession& session) {
  std::string all;
  for (const auto& line : session.console()) all += line + "\n";
  return all;
}

// Where mrsim-opt and the other programs were built.
std::string Programs() {
  return std::filesystem::path(BinaryPath("bin/mrsim-opt"))
      .parent_path()
      .string();
}

// A small run on the 11-module snake, as the window sets it up.
OptimiseOptions SnakeRun(const std::string& dir, const std::string& genome) {
  OptimiseOptions o;
  o.scenario_path = SourcePath("scenarios/snake11.xml");
  o.out_dir = dir + "/run";
  o.genome = ReadGenomeFile(SourcePath("scenarios/" + genome));
  o.population = 4;
  o.episode_s = 1;
  // mrsim-opt's progress messages (each run folder hears only its own).
  o.progress_url = testing::TestLcmUrl(7964);
  return o;
}

bool replay_ready(OptimiseSession& session,
                  std::optional<GenerationRow>* replay) {
  *replay = session.TakeReplay();
  return replay->has_value();
}

TEST(OptimiseSession, SpecIsTheMrsimOptCommandLine) {
  OptimiseOptions o;
  o.scenario_path = "snake.xml";
  o.out_dir = "out";
  o.algorithm = "ga";
  o.generations = 500;  // stopped once it is seen going on
  o.farm = true;
  o.lcm_url = "udpm://239.255.76.67:7001?ttl=0";
  const ProcessSpec spec = OptimiseSession::Spec(o, "g.xml");
  EXPECT_EQ(spec.program, "mrsim-opt");
  EXPECT_EQ(spec.args[0], "snake.xml");
  EXPECT_TRUE(Has(spec.args, "--farm"));
  EXPECT_TRUE(Has(spec.args, o.lcm_url));
  EXPECT_TRUE(Has(spec.args, "ga"));
  EXPECT_FALSE(Has(spec.args, "--jump-to"));
  EXPECT_FALSE(Has(spec.args, "--islands"))
      << "one island: mrsim-opt's default";
  o.islands = 2;
  const std::vector<std::string> islands =
      OptimiseSession::Spec(o, "g.xml").args;
  const auto at = std::find(islands.begin(), islands.end(), "--islands");
  ASSERT_NE(at, islands.end());
  ASSERT_NE(at + 1, islands.end());
  EXPECT_EQ(*(at + 1), "2");
  o.jump_to = 2;
  EXPECT_TRUE(Has(OptimiseSession::Spec(o, "g.xml").args, "--jump-to"));
  o.algorithm = "hillclimb";
  EXPECT_THROW(OptimiseSession::Spec(o, "g.xml"), std::invalid_argument);
  o.algorithm = "ga";
  o.population = 0;
  EXPECT_THROW(OptimiseSession::Spec(o, "g.xml"), std::invalid_argument);
}

TEST(OptimiseSession, SpecWithATaskPassesTheTaskInsteadOfTheDesign) {
  OptimiseOptions o;
  o.task = "pole";
  o.out_dir = "out";
  o.base_gait.clear();  // the picker's choice: the task's own gait
  const std::vector<std::string> args = OptimiseSession::Spec(o, "g.xml").args;
  ASSERT_GE(args.size(), 2u);
  EXPECT_EQ(args[0], "--task");
  EXPECT_EQ(args[1], "pole");
  EXPECT_TRUE(Has(args, "--genome"));
  EXPECT_FALSE(Has(args, "--gait")) << "mrsim-opt takes the task's gait";
  o.base_gait = "serpenoid";
  EXPECT_TRUE(Has(OptimiseSession::Spec(o, "g.xml").args, "serpenoid"));
  o.task.clear();  // neither a task nor a saved design
  EXPECT_THROW(OptimiseSession::Spec(o, "g.xml"), std::invalid_argument);
}

TEST(OptimiseSession, TheDesignsLuaScriptOrANetworkBringTheirOwnGenes) {
  OptimiseOptions o;
  o.scenario_path = "snake.xml";
  o.out_dir = "out";
  o.controller = "lua";
  std::vector<std::string> args = OptimiseSession::Spec(o, "g.xml").args;
  EXPECT_TRUE(Has(args, "lua:out/studio.controller.lua"));
  EXPECT_FALSE(Has(args, "--genome")) << "the script's params are the genes";
  EXPECT_EQ(OptimiseSession::BestFileName(o), "best_controller.lua");
  o.controller = "mlp:8";
  args = OptimiseSession::Spec(o, "g.xml").args;
  EXPECT_TRUE(Has(args, "--controller"));
  EXPECT_TRUE(Has(args, "mlp:8"));
  EXPECT_EQ(OptimiseSession::BestFileName(o), "best_network.xml");
  o.controller = "gait";
  EXPECT_TRUE(Has(OptimiseSession::Spec(o, "g.xml").args, "--genome"));
  EXPECT_EQ(OptimiseSession::BestFileName(o), "best_gait.xml");
}

TEST(OptimiseSession, ALuaScriptsParamsAreOptimisedAsTheWindowStartsIt) {
  const std::string dir = TempDir("optimise_session_lua");
  OptimiseSession session({Programs()});
  OptimiseOptions o = SnakeRun(dir, "forward_gait.genome.xml");
  o.controller = "lua";
  std::ifstream in(SourcePath("examples/optimise/serpenoid_params.lua"));
  std::stringstream script;
  script << in.rdbuf();
  o.lua_source = script.str();
  o.algorithm = "random";
  o.generations = 1;
  o.population = 2;
  o.episode_s = 0.5;
  session.Start(o);
  const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!session.progress().finished &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  session.Poll();
  const std::string console = Console(session);
  ASSERT_TRUE(session.progress().finished) << console;
  EXPECT_EQ(session.progress().exit_code, 0) << console;
  ASSERT_EQ(session.progress().rows.size(), 1u) << console;
  EXPECT_TRUE(session.BestGenes().count("amplitude")) << console;
  EXPECT_TRUE(std::filesystem::exists(o.out_dir + "/best_controller.lua"));
  EXPECT_FALSE(std::filesystem::exists(o.out_dir + "/studio.genome.xml"));

  // A design without a script cannot optimise one.
  o.lua_source.clear();
  EXPECT_THROW(session.Start(o), std::invalid_argument);
}

// The panel's figures come from mrsim-opt's opt_progress_t, not its text:
// only the messages of the panel's own run folder count, and a generation
// read back from the checkpoint has workers but no rate or ETA yet.
TEST(OptimiseSession, ProgressMessagesOfItsOwnRunFillThePanelsFigures) {
  opt_progress_t m{};
  m.out_dir = "/runs/a";
  m.evals_per_second = 5.2;
  m.workers = 2;
  m.eta = "1m12s";
  OptimiseProgress progress;
  EXPECT_FALSE(TakeOptProgress(m, "/runs/b", &progress));
  EXPECT_EQ(progress.workers, 0);
  ASSERT_TRUE(TakeOptProgress(m, "/runs/a", &progress));
  EXPECT_EQ(progress.evals_per_s, 5.2);
  EXPECT_EQ(progress.workers, 2);
  EXPECT_EQ(progress.eta, "1m12s");
  m.replayed = true;
  m.workers = 3;
  m.evals_per_second = 0;
  m.eta = "?";
  ASSERT_TRUE(TakeOptProgress(m, "/runs/a", &progress));
  EXPECT_EQ(progress.workers, 3);
  EXPECT_EQ(progress.evals_per_s, 5.2);
  EXPECT_EQ(progress.eta, "1m12s");
}

TEST(OptimiseSession, SpecPublishesProgressOnThePanelsUrl) {
  OptimiseOptions o;
  o.scenario_path = "snake.xml";
  o.out_dir = "out";
  o.lcm_url = "udpm://239.255.76.67:7001?ttl=0";
  auto url_of = [](const std::vector<std::string>& args) {
    const auto at = std::find(args.begin(), args.end(), "--progress-url");
    return at != args.end() && at + 1 != args.end() ? *(at + 1) : std::string();
  };
  EXPECT_EQ(url_of(OptimiseSession::Spec(o, "g.xml").args), o.lcm_url);
  o.progress_url = "udpm://239.255.76.67:7002?ttl=0";
  EXPECT_EQ(url_of(OptimiseSession::Spec(o, "g.xml").args), o.progress_url);
}

TEST(OptimiseSession, ReadsGenerationsAndStopsAtAHalfWrittenLine) {
  const std::string csv =
      "generation,best,mean,worst,best_so_far,failed,A_pitch,T\n"
      "0,0.5,0.25,0,0.5,0,1,4\n"
      "1,0.75,0.5,0.125,0.75,1,0.9,3.5\n"
      "2,0.7,0.6";
  const auto rows = OptimiseSession::ParseGenerations(csv);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].generation, 1);
  EXPECT_EQ(rows[1].best, 0.75);
  EXPECT_EQ(rows[1].failed, 1);
  EXPECT_EQ(rows[1].genes.at("T"), 3.5);
  EXPECT_THROW(OptimiseSession::ParseGenerations(
                   "generation,best,mean,worst,best_so_far,failed\n"
                   "0,x,0,0,0,0\n"),
               std::runtime_error);
  // A run with islands names each row's island last: not a gene.
  const auto islands = OptimiseSession::ParseGenerations(
      "generation,best,mean,worst,best_so_far,failed,T,island\n"
      "0,0.5,0.25,0,0.5,0,4,0\n"
      "1,0.4,0.25,0,0.5,0,3,1\n");
  ASSERT_EQ(islands.size(), 2u);
  EXPECT_EQ(islands[1].genes.size(), 1u);
  EXPECT_EQ(islands[1].genes.at("T"), 3);
}

TEST(OptimiseSession, ATwoGenerationRunCompletesWithItsProgressAndBest) {
  const std::string dir = TempDir("optimise_session");
  OptimiseSession session({Programs()});
  OptimiseOptions o = SnakeRun(dir, "forward_gait.genome.xml");
  o.algorithm = "cmaes";
  o.generations = 2;
  session.Start(o);
  const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!session.progress().finished &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  session.Poll();  // the last generations.csv
  std::string console = Console(session);
  ASSERT_TRUE(session.progress().finished) << console;
  EXPECT_EQ(session.progress().exit_code, 0) << console;
  ASSERT_EQ(session.progress().rows.size(), 2u) << console;
  EXPECT_GT(session.progress().evals_per_s, 0) << console;
  EXPECT_GE(session.progress().workers, 1);
  const auto best = session.BestGenes();
  ASSERT_TRUE(best.count("A_pitch")) << console;
  EXPECT_TRUE(std::filesystem::exists(o.out_dir + "/best_gait.xml"));
  EXPECT_TRUE(std::filesystem::exists(o.out_dir + "/studio.genome.xml"));

  // Jump to a generation the run has: its best at once, nothing restarts.
  session.Jump(1, o);
  EXPECT_FALSE(session.progress().running);
  auto replay = session.TakeReplay();
  ASSERT_TRUE(replay.has_value());
  EXPECT_EQ(replay->generation, 0);
  EXPECT_EQ(replay->genes, session.progress().rows[0].genes);
  EXPECT_FALSE(session.TakeReplay().has_value());  // handed over once

  // Jump beyond it: mrsim-opt resumes from the checkpoint up to there, and
  // that generation's best is handed over when it is written.
  o.generations = 3;
  session.Jump(3, o);
  EXPECT_TRUE(session.progress().running);
  EXPECT_FALSE(session.TakeReplay().has_value());
  while (!replay_ready(session, &replay) &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  console = Console(session);
  ASSERT_TRUE(replay.has_value()) << console;
  EXPECT_EQ(replay->generation, 2);
  ASSERT_NE(session.Row(2), nullptr);
  EXPECT_EQ(replay->genes, session.Row(2)->genes);
  // The first two generations came back from the checkpoint unchanged.
  EXPECT_NE(console.find("from checkpoint"), std::string::npos) << console;

  // Other settings in the same folder: the run fails, and the panel has
  // mrsim-opt's reason, not only its exit code.
  while (session.progress().running && std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  o.population = 5;
  session.Start(o);
  while (!session.progress().finished &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  ASSERT_TRUE(session.progress().finished) << Console(session);
  EXPECT_NE(session.progress().exit_code, 0);
  EXPECT_NE(session.progress().failure.find(
                "made with other settings: population=4 (this run: 5)"),
            std::string::npos)
      << session.progress().failure;
  EXPECT_EQ(session.progress().failure.find("mrsim-opt:"), std::string::npos)
      << session.progress().failure;
}

TEST(OptimiseSession, AFarmWithoutWorkersIsFlaggedAsStalled) {
  const std::string dir = TempDir("optimise_stall");
  OptimiseSession session({Programs()});
  OptimiseOptions o = SnakeRun(dir, "forward_gait.genome.xml");
  o.generations = 2;
  o.farm = true;  // and no mrsim-worker anywhere on this URL
  o.lcm_url = testing::TestLcmUrl(7969);
  const WallTime t0 = WallClock::now();
  session.Start(o, t0);
  session.Poll(0, AfterSeconds(t0, 20));
  EXPECT_EQ(session.StallWarning(AfterSeconds(t0, 20)), "");
  session.Poll(0, AfterSeconds(t0, 42));
  ASSERT_TRUE(session.progress().running) << Console(session);
  const std::string warning = session.StallWarning(AfterSeconds(t0, 42));
  EXPECT_NE(warning.find("no progress for 42 s: are workers alive?"),
            std::string::npos)
      << warning;
  EXPECT_NE(warning.find("no workers reported yet"), std::string::npos)
      << warning;
  session.Stop();
  EXPECT_EQ(session.StallWarning(AfterSeconds(t0, 42)), "");
  // Stopped, not finished or failed: the panel says so.
  EXPECT_TRUE(session.progress().stopped);
  EXPECT_FALSE(session.progress().finished);
}

TEST(OptimiseSession, WatchingABestWithBodyGenesRunsItsBodyWhileTheRunGoesOn) {
  const std::string dir = TempDir("optimise_watch_body");
  const std::string bin = Programs();
  OptimiseSession session({bin});
  OptimiseOptions o = SnakeRun(dir, "snake_body.genome.xml");
  // Never the design's eleven modules: the best's body is another one.
  GeneSpec& count = o.genome.genes[o.genome.Find("module_count")];
  count.lower = 5;
  count.upper = 8;
  count.start = 6;
  o.algorithm = "ga";
  o.generations = 500;  // stopped once it is seen going on
  session.Start(o);
  const auto end = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (session.progress().rows.empty() && session.progress().running &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
  }
  ASSERT_FALSE(session.progress().rows.empty()) << Console(session);
  const auto row = session.Best();
  ASSERT_TRUE(row.has_value());
  const BestReplay best = MakeBestReplay(session.options(), *row);
  EXPECT_TRUE(best.body);
  const size_t modules = best.scenario.robots[0].modules.size();
  EXPECT_EQ(static_cast<double>(modules), row->genes.at("module_count"));

  const std::string url = testing::TestLcmUrl(7970);
  LiveRunner runner({bin});
  RunOptions form;
  form.lcm_url = url;
  form.paused = true;
  runner.Start(WriteBestReplay(best, o.out_dir + "/watch", form));
  LiveSessionOptions so;
  so.sender = "studio-watch-test";
  LiveSession live(so);
  LiveLink link(url, &live);
  auto heard = [&] {
    const LiveRobot* r = live.robot(best.robot);
    return r != nullptr && r->states > 0 && r->gait.has_value();
  };
  while (!heard() && std::chrono::steady_clock::now() < end) {
    link.Poll(20);
    runner.Poll();
    session.Poll();
  }
  ASSERT_TRUE(heard());
  const LiveRobot* robot = live.robot(best.robot);
  EXPECT_EQ(static_cast<size_t>(robot->state.num_modules), modules);
  const std::vector<double> p = best.gait.parameters.ToVector();
  for (int i = 0; i < 7; ++i) {
    EXPECT_DOUBLE_EQ(robot->gait->parameters[i], p[i]) << i;
  }

  // The optimisation goes on beside the run.
  session.Poll();
  const size_t done = session.progress().rows.size();
  ASSERT_TRUE(session.progress().running) << Console(session);
  while (session.progress().rows.size() <= done &&
         std::chrono::steady_clock::now() < end) {
    session.Poll(100);
    runner.Poll();
  }
  EXPECT_GT(session.progress().rows.size(), done) << Console(session);
  EXPECT_TRUE(runner.running());
  session.Stop();
  runner.Stop();
}

}  // namespace
}  // namespace mrsim::studio
