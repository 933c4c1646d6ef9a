// The farm and the master as real processes: mrsim-opt and mrsim-worker
// over LCM on loopback (ports 7700-7749), short real snake episodes.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> OptArgs(const std::string& out) {
  return {BinaryPath("optimizer/process/mrsim-opt"),
          SourcePath("scenarios/snake11.xml"),
          "--genome",
          SourcePath("scenarios/forward_gait.genome.xml"),
          "--algorithm",
          "ga",
          "--generations",
          "4",
          "--population",
          "6",
          "--seed",
          "17",
          "--episode",
          "2",
          "--out",
          out};
}

std::vector<std::string> With(std::vector<std::string> args,
                              const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// The files a run's result consists of must match byte for byte.
void ExpectSameResult(const std::string& a, const std::string& b) {
  for (const char* f :
       {"/generations.csv", "/evaluations.csv", "/best_gait.xml",
        "/best_scenario.xml", "/best_genome.xml"}) {
    const std::string x = ReadAll(a + f);
    EXPECT_FALSE(x.empty()) << a << f;
    EXPECT_EQ(x, ReadAll(b + f)) << f;
  }
}

std::string LocalReference(const std::string& name) {
  const std::string dir = TempDir(name);
  ChildProcess local(With(OptArgs(dir), {"--workers", "local:2"}),
                     dir + "/log.txt");
  EXPECT_EQ(local.Wait(90), 0) << local.Output();
  return dir;
}

TEST(FarmProcess, KilledAndLateWorkersGiveTheLocalResult) {
  const std::string local = LocalReference("farm_local_ref");
  const std::string url = TestLcmUrl(7701);
  const std::string dir = TempDir("farm_run");
  auto worker = [&](const std::string& id) {
    return std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("optimizer/process/mrsim-worker"),
                                 "--lcm-url", url, "--id", id},
        dir + "/" + id + ".log");
  };
  auto w1 = worker("w1");
  auto w2 = worker("w2");
  // Small chunks so the payload travels in several acknowledged pieces.
  ChildProcess master(
      With(OptArgs(dir), {"--farm", "--lcm-url", url, "--worker-timeout", "1",
                          "--chunk-size", "4000"}),
      dir + "/master.log");
  ASSERT_TRUE(master.WaitForOutput("generation 1 of 4", 60)) << master.Output();
  // Mid-generation 2: w1 dies and w2 freezes (a suspended host), so the run
  // cannot end before the late worker w3 has joined, fetched the payload
  // and taken over their jobs, however slowly each process gets scheduled.
  w1->Signal(SIGKILL);
  w2->Signal(SIGSTOP);
  auto w3 = worker("w3");
  EXPECT_TRUE(master.WaitForOutput("worker w1 is gone", 60)) << master.Output();
  EXPECT_TRUE(master.WaitForOutput("worker w3 is ready", 60))
      << master.Output();
  // w2 comes back: its stale answers must not change anything.
  w2->Signal(SIGCONT);
  ASSERT_EQ(master.Wait(90), 0) << master.Output();
  EXPECT_NE(w3->Output().find("ready"), std::string::npos) << w3->Output();
  ExpectSameResult(local, dir);
}

// A signed farm checked by --verify: a worker without the key gets no job
// and a worker that lies is outvoted and dropped; the result is the local
// run's.
TEST(FarmProcess, SignedVerifiedFarmShutsOutIntrudersAndLiars) {
  const std::string local = LocalReference("farm_signed_local_ref");
  const std::string url = TestLcmUrl(7705);
  const std::string dir = TempDir("farm_signed");
  const std::string key = dir + "/farm.key";
  ChildProcess keygen({BinaryPath("launcher/mrsim"), "keygen", key});
  ASSERT_EQ(keygen.Wait(30), 0);
  auto worker = [&](const std::string& id, std::vector<std::string> more) {
    std::vector<std::string> argv{BinaryPath("optimizer/process/mrsim-worker"),
                                  "--lcm-url", url, "--id", id};
    argv.insert(argv.end(), more.begin(), more.end());
    return std::make_unique<ChildProcess>(argv, dir + "/" + id + ".log");
  };
  auto w1 = worker("w1", {"--key-file", key});
  auto w2 = worker("w2", {"--key-file", key});
  auto liar = worker("liar", {"--key-file", key, "--test-lie", "1"});
  auto intruder = worker("intruder", {});
  ChildProcess master(With(OptArgs(dir), {"--farm", "--lcm-url", url,
                                          "--key-file", key, "--verify", "1"}),
                      dir + "/master.log");
  ASSERT_EQ(master.Wait(120), 0) << master.Output();
  EXPECT_NE(master.Output().find("worker liar dropped for this run"),
            std::string::npos)
      << master.Output();
  EXPECT_EQ(master.Output().find("worker intruder"), std::string::npos)
      << master.Output();
  intruder->Stop();
  EXPECT_NE(intruder->Output().find("stopping; 0 jobs done"), std::string::npos)
      << intruder->Output();
  ExpectSameResult(local, dir);
}

// With islands the master keeps the next island's generation on the farm
// while one ends; the result is still the local run's.
TEST(FarmProcess, IslandsOnTheFarmGiveTheLocalResult) {
  const std::string local = TempDir("farm_islands_local");
  ChildProcess reference(
      With(OptArgs(local), {"--workers", "local:2", "--islands", "2"}),
      local + "/log.txt");
  ASSERT_EQ(reference.Wait(90), 0) << reference.Output();
  const std::string url = TestLcmUrl(7704);
  const std::string dir = TempDir("farm_islands");
  std::vector<std::unique_ptr<ChildProcess>> workers;
  for (const char* id : {"w1", "w2"}) {
    workers.push_back(std::make_unique<ChildProcess>(
        std::vector<std::string>{BinaryPath("optimizer/process/mrsim-worker"),
                                 "--lcm-url", url, "--id", id},
        dir + "/" + id + ".log"));
  }
  ChildProcess master(
      With(OptArgs(dir), {"--farm", "--lcm-url", url, "--islands", "2"}),
      dir + "/master.log");
  ASSERT_EQ(master.Wait(120), 0) << master.Output();
  EXPECT_NE(master.Output().find("generation 4 of 4"), std::string::npos)
      << master.Output();
  ExpectSameResult(local, dir);
}

TEST(OptimizerProcess, MasterKilledAndRestartedEndsWithTheSameResult) {
  const std::string local = LocalReference("opt_resume_ref");
  const std::string dir = TempDir("opt_resume");
  const auto args = With(OptArgs(dir), {"--workers", "local:2"});
  {
    ChildProcess first(args, dir + "/first.log");
    ASSERT_TRUE(first.WaitForOutput("generation 2 of 4", 60)) << first.Output();
    first.Signal(SIGKILL);
    EXPECT_EQ(first.Wait(10), 128 + SIGKILL);
  }
  ChildProcess second(args, dir + "/second.log");
  ASSERT_EQ(second.Wait(90), 0) << second.Output();
  EXPECT_NE(second.Output().find("from checkpoint"), std::string::npos)
      << second.Output();
  ExpectSameResult(local, dir);
}

TEST(OptimizerProcess, SigintStopsCleanlyKeepingCompletedGenerations) {
  const std::string dir = TempDir("opt_sigint");
  ChildProcess p(With(OptArgs(dir), {"--workers", "local:1"}),
                 dir + "/log.txt");
  ASSERT_TRUE(p.WaitForOutput("generation 1 of 4", 60)) << p.Output();
  p.Signal(SIGINT);
  // Unfinished: exit 130, as a shell reports an interrupted command.
  EXPECT_EQ(p.Wait(30), 128 + SIGINT) << p.Output();
  EXPECT_NE(p.Output().find("run the same command to continue"),
            std::string::npos)
      << p.Output();
  EXPECT_NE(ReadAll(dir + "/checkpoint.txt").find("gen 0 "), std::string::npos);
  // The completed generations' best, to take away now.
  EXPECT_NE(p.Output().find("best so far"), std::string::npos) << p.Output();
  EXPECT_NE(ReadAll(dir + "/best_gait.xml").find("<gait"), std::string::npos);
  EXPECT_NE(ReadAll(dir + "/replay.launch").find("<launch"), std::string::npos);
}

// Episodes far longer than anyone waits: Ctrl-C stops them, it does not
// wait for them to end.
TEST(OptimizerProcess, SigintCutsLongEpisodesShort) {
  const std::string dir = TempDir("opt_sigint_long");
  std::vector<std::string> args = OptArgs(dir + "/out");
  args[13] = "100000";  // --episode
  ChildProcess p(args, dir + "/log.txt");
  ASSERT_TRUE(p.WaitForOutput("100000 s episodes", 60)) << p.Output();
  p.Signal(SIGINT);
  EXPECT_EQ(p.Wait(60), 128 + SIGINT) << p.Output();
  EXPECT_NE(p.Output().find("stopped before the first generation"),
            std::string::npos)
      << p.Output();
}

TEST(OptimizerProcess, BadInputExitsWithTwoNamingTheProblem) {
  const std::string dir = TempDir("opt_bad_input");
  {
    std::ofstream(dir + "/bad.genome.xml")
        << "<genome>\n  <gene name=\"T\" lower=\"1\" upper=\"oops\" "
           "start=\"2\"/>\n</genome>\n";
  }
  std::vector<std::string> args = OptArgs(dir + "/out");
  args[3] = dir + "/bad.genome.xml";
  ChildProcess p(args, dir + "/log.txt");
  EXPECT_EQ(p.Wait(30), 2);
  EXPECT_NE(p.Output().find("bad.genome.xml:2"), std::string::npos)
      << p.Output();
  ChildProcess q(With(OptArgs(dir + "/out2"), {"--algorithm", "cmaes"}),
                 dir + "/log2.txt");
  EXPECT_EQ(q.Wait(30), 2);
  EXPECT_NE(q.Output().find("algorithm"), std::string::npos) << q.Output();
}

// A module_count genome that grows the snake into the ball lying behind
// it: mrsim-opt says why those individuals failed (the parts, once per
// line, not per individual) and, in its summary, the flag that runs them;
// with --allow-overlap they run.
TEST(OptimizerProcess,
     SaysWhichPartsOverlapInFailedBodiesAndRunsThemIfAllowed) {
  const std::string dir = TempDir("opt_overlap_reason");
  Scenario scenario;
  scenario.robots.push_back(MakeChain(ChainOptions{}));  // 11 modules
  ChainOptions longer;
  longer.modules = 14;
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.05, 0.05, 0.05);
  ball.position = MakeChain(longer).modules[12].position;
  scenario.scene_objects.push_back(ball);
  WriteScenarioFile(scenario, dir + "/ball_behind.xml");
  std::ofstream(dir + "/body.genome.xml") << R"(<genome>
  <gene name="module_count" lower="11" upper="14" start="11"/>
</genome>
)";
  auto args = [&](const std::string& out) {
    return std::vector<std::string>{BinaryPath("optimizer/process/mrsim-opt"),
                                    dir + "/ball_behind.xml",
                                    "--genome",
                                    dir + "/body.genome.xml",
                                    "--generations",
                                    "2",
                                    "--population",
                                    "6",
                                    "--episode",
                                    "0.5",
                                    "--workers",
                                    "local:2",
                                    "--out",
                                    dir + "/" + out};
  };
  ChildProcess refused(args("refused"), dir + "/refused.txt");
  ASSERT_EQ(refused.Wait(120), 0) << refused.Output();
  const std::string said = refused.Output();
  EXPECT_NE(said.find(" (overlap at the start: robot 'snake' module 12 "),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("/ scene object 'ball'"), std::string::npos) << said;
  EXPECT_NE(said.find("failed individuals: "), std::string::npos) << said;
  EXPECT_NE(said.find("(--allow-overlap) to run"), std::string::npos) << said;

  ChildProcess allowed(With(args("allowed"), {"--allow-overlap"}),
                       dir + "/allowed.txt");
  ASSERT_EQ(allowed.Wait(120), 0) << allowed.Output();
  EXPECT_EQ(allowed.Output().find("overlap at the start"), std::string::npos)
      << allowed.Output();
  EXPECT_EQ(allowed.Output().find("failed individuals"), std::string::npos)
      << allowed.Output();
}

}  // namespace
}  // namespace mrsim
