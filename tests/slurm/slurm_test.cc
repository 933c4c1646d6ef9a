// The farm through a real Slurm cluster on this host: mrsim-opt --slurm 4
// --hub submits its workers as an array job; mid-run two of its tasks are
// cancelled, two workers are added by hand with scripts/slurm's batch
// script and a third task is requeued (it re-joins); the result equals the
// local run of the same seed, and at the end mrsim-opt has cancelled its own
// job and no other. Needs root (skips otherwise, as tests/farm_net does).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/slurm/slurm_cluster.h"

namespace mrsim::testing {
namespace {

int Port(int port) {
  const char* offset = std::getenv("MRSIM_TEST_PORT_OFFSET");
  return port + (offset != nullptr ? std::atoi(offset) : 0);
}

std::vector<std::string> OptArgs(const std::string& out) {
  return {BinaryPath("optimizer/process/mrsim-opt"),
          SourcePath("scenarios/snake11.xml"), "--genome",
          SourcePath("scenarios/forward_gait.genome.xml"), "--out", out,
          "--episode", "1", "--population", "8",
          // Long enough that the requeued task, held back by Slurm and
          // then started, still finds the run going under load.
          "--generations", "48", "--seed", "11"};
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos;
       at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

TEST(SlurmFarm, WorkersCancelledAndAddedMidRunGiveTheLocalResult) {
  std::string why;
  if (!SlurmCluster::Available(&why)) GTEST_SKIP() << why;
  const std::string dir = TempDir("slurm_farm");
  const int port = Port(8800);  // slurmctld; +1..+4 slurmd; +10 the hub
  SlurmCluster cluster(port);
  const int hub = port + 10;
  const std::string url = fmt::format("tcpq://127.0.0.1:{}", hub);
  const std::string prefix = "SLURM_TEST";

  std::vector<std::string> farm_args = OptArgs(dir + "/farm");
  for (const std::string& a :
       {std::string("--farm"), std::string("--slurm"), std::string("4"),
        std::string("--slurm-opt"), std::string("time=10"),
        std::string("--hub"), std::to_string(hub), std::string("--lcm-url"),
        url, std::string("--prefix"), prefix}) {
    farm_args.push_back(a);
  }
  ChildProcess opt(farm_args, dir + "/opt.log");
  ASSERT_TRUE(opt.WaitForOutput("Slurm array job", 60.0))
      << opt.Output() << cluster.Logs();
  std::smatch m;
  const std::string said = opt.Output();
  ASSERT_TRUE(std::regex_search(said, m, std::regex("Slurm array job (\\d+)")));
  const std::string job = m[1];

  // Two of its tasks go (as a preemption or a user's scancel would) ...
  ASSERT_TRUE(opt.WaitForOutput("generation 2 of 48", 120.0))
      << opt.Output() << cluster.Logs();
  for (const char* task : {"_0", "_1"}) {
    const CommandOutput out = cluster.Run({"scancel", job + task});
    ASSERT_EQ(out.exit_code, 0) << out.output;
  }
  // ... and two join, submitted by hand with the batch script.
  const CommandOutput added = cluster.Run(
      {"sbatch", "--parsable", "--array=0-1",
       "--output=" + dir + "/added-%A_%a.log",
       "--export=ALL,MRSIM_LCM_URL=" + url + ",MRSIM_OPT_PREFIX=" + prefix +
           ",MRSIM_WORKER=" + BinaryPath("optimizer/process/mrsim-worker"),
       SourcePath("scripts/slurm/mrsim-worker.sbatch")});
  ASSERT_EQ(added.exit_code, 0) << added.output;
  const std::string added_job =
      added.output.substr(0, added.output.find_first_of(";\n"));

  // One more is requeued, as Slurm does when its node fails: it comes
  // back as a new worker. Slurm requeues only a task that has started
  // ("Job is pending execution" otherwise), and under load a node can take
  // its time to start it.
  ASSERT_TRUE(WaitUntil(
      [&] {
        return cluster.Tasks(job).find("_2 RUNNING") != std::string::npos;
      },
      120.0, 0.1))
      << cluster.Tasks(job) << opt.Output() << cluster.Logs();
  const CommandOutput requeued =
      cluster.Run({"scontrol", "requeue", job + "_2"});
  ASSERT_EQ(requeued.exit_code, 0) << requeued.output;
  // Slurm holds a requeued job back for a while (its begin time); the test
  // lets it start as soon as a node is free.
  ASSERT_TRUE(WaitUntil(
      [&] {
        return cluster.Tasks(job).find("_2 PENDING") != std::string::npos;
      },
      60.0, 0.1))
      << cluster.Tasks(job);
  cluster.Run({"scontrol", "update", "JobId=" + job + "_2", "StartTime=now"});

  ASSERT_EQ(opt.Wait(300.0), 0) << opt.Output() << cluster.Logs();
  const std::string farm_output = opt.Output();
  // Four array tasks, the two added workers and the requeued task joined.
  EXPECT_GE(Count(farm_output, " joined"), 7) << farm_output;
  EXPECT_NE(farm_output.find("cancelled Slurm job " + job), std::string::npos)
      << farm_output;
  EXPECT_NE(farm_output.find(" running, "), std::string::npos);
  // mrsim-opt cancelled its own job, not the one added by hand.
  EXPECT_TRUE(WaitUntil([&] { return cluster.Tasks(job).empty(); }, 60.0, 0.2))
      << cluster.Tasks(job);
  EXPECT_NE(cluster.Tasks(added_job), "");

  ChildProcess local(OptArgs(dir + "/local"), dir + "/local.log");
  ASSERT_EQ(local.Wait(300.0), 0) << local.Output();
  const std::string farm_best = ReadFileText(dir + "/farm/best_genome.xml");
  EXPECT_FALSE(farm_best.empty());
  EXPECT_EQ(farm_best, ReadFileText(dir + "/local/best_genome.xml"));
  EXPECT_EQ(ReadFileText(dir + "/farm/evaluations.csv"),
            ReadFileText(dir + "/local/evaluations.csv"));
}

}  // namespace
}  // namespace mrsim::testing
