// FarmLink, the farm's one meeting point with LCM, on multicast loopback
// (LCM port 7703, ttl=0): what arrives in a burst must reach the handlers,
// however many messages wait for Handle().
#include "optimizer/farm/farm_link.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "optimizer/farm/farm_channels.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using Clock = std::chrono::steady_clock;

opt_job_t Job(int k) {
  opt_job_t job{};
  job.run_id = "run";
  job.scenario_hash = "hash";
  job.worker_id = "w" + std::to_string(k % 250);
  job.job_id = k;
  job.generation = 1;
  job.index = k;
  job.genome = {0.1 * k, -0.2};
  job.gene_count = 2;
  return job;
}

// Datagrams read from UDP sockets in this network namespace so far (the
// kernel counts one each time a socket's reader takes one).
long long UdpDatagramsRead() {
  std::ifstream snmp("/proc/net/snmp");
  std::string line;
  int udp_lines = 0;
  while (std::getline(snmp, line)) {
    if (line.rfind("Udp:", 0) != 0 || ++udp_lines < 2) continue;
    std::istringstream fields(line.substr(4));
    long long in = -1;
    fields >> in;
    return in;
  }
  return -1;
}

// A generation's jobs go out in one burst; a process of fake workers (or a
// worker on udpm, which hears every job) has them all read off the socket
// by LCM's receive thread before it handles the first. LCM kept 30 of them
// per channel by default and dropped the rest; the farm lost most of every
// burst though the kernel had delivered it (docs/scaling.md).
TEST(FarmLink, ABurstReadByLcmBeforeItIsHandledIsKeptWhole) {
  const long long read_before = UdpDatagramsRead();
  ASSERT_GE(read_before, 0) << "no /proc/net/snmp";
  int heard = 0, malformed = 0;
  FarmLink::Handlers handlers;
  handlers.job = [&](const opt_job_t& job) {
    EXPECT_EQ(job.job_id, heard);  // in order, none lost
    ++heard;
  };
  handlers.malformed = [&] { ++malformed; };
  FarmLink link(testing::TestLcmUrl(7703), "BURST", handlers);
  constexpr int kJobs = 256;  // fits the smallest receive buffer it gets
  FarmOutbox out;
  for (int k = 0; k < kJobs; ++k) out.jobs.push_back(Job(k));
  link.Publish(out);  // multicast loopback: to ourselves
  // Let LCM's receive thread read all of them before we handle any.
  const auto deadline = Clock::now() + std::chrono::seconds(20);
  while (UdpDatagramsRead() - read_before < kJobs && Clock::now() < deadline) {
    std::this_thread::yield();
  }
  while (heard < kJobs && Clock::now() < deadline) link.Handle(10);
  EXPECT_EQ(heard, kJobs);
  EXPECT_EQ(malformed, 0);
}

// Jobs go on the job channel of their worker's shard and a worker
// subscribes to its own: on tcpq the hub then copies a job to the workers
// of one shard instead of to every worker (docs/scaling.md).
TEST(FarmLink, AWorkerHearsOnlyTheJobsOfItsOwnShard) {
  ASSERT_NE(JobShard("w1"), JobShard("w2"));
  std::vector<std::string> heard;
  FarmLink::Handlers handlers;
  handlers.job = [&](const opt_job_t& job) { heard.push_back(job.worker_id); };
  handlers.job_workers = {"w1"};
  FarmLink link(testing::TestLcmUrl(7706), "SHARD", handlers);
  FarmOutbox out;
  for (int k = 0; k < 4; ++k) {
    opt_job_t job = Job(k);
    job.worker_id = k % 2 == 0 ? "w1" : "w2";
    out.jobs.push_back(job);
  }
  link.Publish(out);
  const auto deadline = Clock::now() + std::chrono::seconds(20);
  while (heard.size() < 2 && Clock::now() < deadline) link.Handle(10);
  link.Handle(50);  // anything more that was coming
  EXPECT_EQ(heard, (std::vector<std::string>{"w1", "w1"}));
  EXPECT_EQ(FarmChannels("P").JobChannel(JobShard("w1")).rfind("P_JOB_", 0),
            0u);
}

}  // namespace
}  // namespace mrsim
