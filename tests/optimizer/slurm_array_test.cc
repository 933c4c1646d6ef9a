// mrsim-opt --slurm's logic against a fake scheduler: what is submitted,
// how the progress line counts the array's tasks, that squeue is asked at
// most once per interval of a fake clock, and that the run's own job (and
// no other) is cancelled once when the run ends.
#include "optimizer/slurm/slurm_array.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "optimizer/slurm/farm_cluster.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

// Answers as a cluster would; records every call.
class FakeSlurm : public SlurmRunner {
 public:
  CommandOutput Run(const std::vector<std::string>& argv) override {
    calls.push_back(argv);
    CommandOutput out;
    out.exit_code = 0;
    const auto it = answers.find(argv.at(0));
    if (it != answers.end()) out = it->second;
    return out;
  }
  int CallsOf(const std::string& program) const {
    return static_cast<int>(
        std::count_if(calls.begin(), calls.end(),
                      [&](const auto& c) { return c.at(0) == program; }));
  }
  void Answer(const std::string& program, int exit_code,
              const std::string& text) {
    answers[program].exit_code = exit_code;
    answers[program].output = text;
  }
  std::vector<std::vector<std::string>> calls;
  std::map<std::string, CommandOutput> answers;
};

// Hands the calls on to a FakeSlurm the test keeps (FarmCluster owns its
// runner).
class Forward : public SlurmRunner {
 public:
  explicit Forward(SlurmRunner& to) : to_(to) {}
  CommandOutput Run(const std::vector<std::string>& argv) override {
    return to_.Run(argv);
  }

 private:
  SlurmRunner& to_;
};

bool Has(const std::vector<std::string>& argv, const std::string& arg) {
  return std::find(argv.begin(), argv.end(), arg) != argv.end();
}

SlurmArraySettings FourWorkers() {
  SlurmArraySettings s;
  s.tasks = 4;
  s.options = {"partition=debug", "--time=1:00:00", "cpus-per-task=2"};
  s.command = "exec mrsim-worker --lcm-url tcpq://head:5701";
  s.poll_interval = 5.0;
  return s;
}

TEST(SlurmArray, SubmitsTheWorkersAsOneRequeueableArrayWithTheUsersOptions) {
  FakeSlurm slurm;
  slurm.Answer("sbatch", 0, "4242;cluster\n");
  SlurmArray array(slurm, FourWorkers());
  array.Submit();
  EXPECT_EQ(array.job_id(), "4242");
  ASSERT_EQ(slurm.CallsOf("sbatch"), 1);
  const auto& argv = slurm.calls.at(0);
  for (const char* arg :
       {"--parsable", "--array=0-3", "--requeue", "--partition=debug",
        "--time=1:00:00", "--cpus-per-task=2",
        "--wrap=exec mrsim-worker --lcm-url tcpq://head:5701"}) {
    EXPECT_TRUE(Has(argv, arg)) << arg;
  }
}

TEST(SlurmArray, ARefusedSubmissionSaysWhatSbatchSaid) {
  FakeSlurm slurm;
  slurm.Answer("sbatch", 1,
               "sbatch: error: invalid partition specified: debug\n");
  SlurmArray array(slurm, FourWorkers());
  try {
    array.Submit();
    FAIL() << "no error";
  } catch (const SlurmError& e) {
    EXPECT_NE(std::string(e.what()).find("invalid partition specified"),
              std::string::npos)
        << e.what();
  }
  slurm.Answer("sbatch", 0, "Submitted batch job\n");
  EXPECT_THROW(array.Submit(), SlurmError);  // no job id in the answer
  EXPECT_EQ(slurm.CallsOf("scancel"), 0);    // nothing to cancel
}

TEST(SlurmArray, OptionsTheArraySetsItselfAreRefused) {
  EXPECT_EQ(NormaliseSbatchOption("account=proj"), "--account=proj");
  EXPECT_EQ(NormaliseSbatchOption("-p debug"), "-p debug");
  EXPECT_THROW(NormaliseSbatchOption("array=0-9"), SlurmError);
  EXPECT_THROW(NormaliseSbatchOption("--wrap=ls"), SlurmError);
  EXPECT_THROW(NormaliseSbatchOption(" "), SlurmError);
}

TEST(SlurmArray, TheProgressLineCountsPendingAndRunningTasks) {
  FakeSlurm slurm;
  slurm.Answer("sbatch", 0, "4242\n");
  SlurmArray array(slurm, FourWorkers());
  array.Submit();
  EXPECT_EQ(array.Describe(), "slurm 4242: 4 submitted");
  slurm.Answer("squeue", 0,
               "4242_0 RUNNING\n4242_1 RUNNING\n4242_[2-3%4] PENDING\n");
  EXPECT_TRUE(array.Poll(0.0));
  EXPECT_EQ(array.Describe(), "slurm 4242: 2 running, 2 pending");
  // A preempted or failed node's task is requeued: it waits again.
  slurm.Answer("squeue", 0,
               "4242_0 RUNNING\n4242_1 REQUEUED\n4242_2 RUNNING\n4242_3 "
               "RUNNING\n");
  EXPECT_TRUE(array.Poll(10.0));
  EXPECT_EQ(array.Describe(), "slurm 4242: 3 running, 1 pending");
  // A scheduler that does not answer leaves the last counts, marked.
  slurm.Answer("squeue", 1, "slurm_load_jobs error: Unable to contact\n");
  EXPECT_TRUE(array.Poll(20.0));
  EXPECT_EQ(array.Describe(),
            "slurm 4242: 3 running, 1 pending (squeue failed: last known)");
  // Once the job left the queue squeue calls its id invalid: none left.
  slurm.Answer("squeue", 1,
               "slurm_load_jobs error: Invalid job id specified\n");
  EXPECT_TRUE(array.Poll(30.0));
  EXPECT_EQ(array.Describe(), "slurm 4242: 0 running, 0 pending");
}

TEST(SlurmArray, SqueueIsAskedAtMostOncePerInterval) {
  FakeSlurm slurm;
  slurm.Answer("sbatch", 0, "4242\n");
  SlurmArray array(slurm, FourWorkers());
  array.Submit();
  EXPECT_TRUE(array.Poll(100.0));
  EXPECT_FALSE(array.Poll(101.0));
  EXPECT_FALSE(array.Poll(104.9));
  EXPECT_TRUE(array.Poll(105.0));
  EXPECT_EQ(slurm.CallsOf("squeue"), 2);
  const auto& squeue = slurm.calls.back();
  EXPECT_TRUE(Has(squeue, "--jobs=4242"));  // this run's job only
}

TEST(SlurmArray, TheRunsOwnJobIsCancelledOnceWhenItEnds) {
  FakeSlurm slurm;
  slurm.Answer("sbatch", 0, "4242\n");
  {
    SlurmArray array(slurm, FourWorkers());
    array.Submit();
    EXPECT_TRUE(array.Cancel());
    EXPECT_TRUE(array.Cancel());
    EXPECT_EQ(array.Describe(), "slurm 4242: cancelled");
    EXPECT_FALSE(array.Poll(1000.0));  // no squeue after the end
  }
  ASSERT_EQ(slurm.CallsOf("scancel"), 1);
  EXPECT_EQ(slurm.calls.back(), (std::vector<std::string>{"scancel", "4242"}));

  // Destroyed without an explicit cancel (an error, Ctrl-C): cancelled too.
  FakeSlurm other;
  other.Answer("sbatch", 0, "77\n");
  {
    SlurmArray array(other, FourWorkers());
    array.Submit();
  }
  ASSERT_EQ(other.CallsOf("scancel"), 1);
  EXPECT_EQ(other.calls.back(), (std::vector<std::string>{"scancel", "77"}));
}

TEST(FarmCluster, WorkersGetTheHubsUrlThePrefixAndTheirCpus) {
  FarmClusterOptions o;
  o.hub_port = 5701;
  o.host = "head";
  o.prefix = "RUN1";
  o.worker_program = "/opt/mrsim/bin/mrsim-worker";
  EXPECT_EQ(WorkerLcmUrl(o), "tcpq://head:5701");
  EXPECT_EQ(WorkerCommandLine(o),
            "exec '/opt/mrsim/bin/mrsim-worker' --lcm-url "
            "'tcpq://head:5701' --prefix 'RUN1' --threads "
            "\"${SLURM_CPUS_PER_TASK:-1}\"");
  o.lcm_url = "tcpq://head.cluster:5701";
  EXPECT_EQ(WorkerLcmUrl(o), "tcpq://head.cluster:5701");
  o.lcm_url = "tcpq://head:7702";
  EXPECT_THROW(WorkerLcmUrl(o), std::invalid_argument);
  o.lcm_url = "udpm://239.255.76.67:7667";
  EXPECT_THROW(WorkerLcmUrl(o), std::invalid_argument);
}

TEST(FarmCluster, SubmitsTheArrayAndCancelsItWhenTheRunEnds) {
  FakeSlurm slurm;
  slurm.Answer("sbatch", 0, "99\n");
  slurm.Answer("squeue", 0, "99_0 RUNNING\n99_1 PENDING\n");
  FarmClusterOptions o;
  o.slurm_tasks = 2;
  o.slurm_options = {"partition=short"};
  o.out_dir = testing::TempDir("farm_cluster_fake");
  o.worker_program = "mrsim-worker";
  std::vector<std::string> said;
  {
    FarmCluster cluster(o, std::make_unique<Forward>(slurm),
                        [&](const std::string& line) { said.push_back(line); });
    EXPECT_EQ(cluster.master_url(), "");  // no hub: LCM's default
    EXPECT_EQ(cluster.ProgressNote(), " | slurm 99: 1 running, 1 pending");
  }
  EXPECT_EQ(slurm.CallsOf("scancel"), 1);
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said.front().find("Slurm array job 99"), std::string::npos);
  EXPECT_NE(said.back().find("cancelled Slurm job 99"), std::string::npos);
}

}  // namespace
}  // namespace mrsim
