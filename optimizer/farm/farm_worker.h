// The worker's side of the farm (mrsim-worker): follows the run a master
// announces, fetches its payload in chunks (asking again for missing ones),
// checks the hash, then runs the jobs addressed to it on its own threads
// and answers with fitness and metrics. Heartbeats go out while episodes
// run, so the master can tell a busy worker from a dead one.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "mrsim/opt_result_t.hpp"
#include "optimizer/episode.h"
#include "optimizer/farm/payload_chunks.h"

namespace mrsim {

struct WorkerSettings {
  std::string prefix = "MRSIM_OPT";
  std::string id;  // unique on the network; default host-pid
  int threads = 1;
  double heartbeat_period = 0.2;  // s
  double request_period = 0.3;    // s between asks for missing chunks
  double run_silence = 3.0;       // s without announcement before following
                                  // another master's run
};

struct WorkerCounters {
  long long jobs_done = 0;
  long long messages_ignored = 0;  // other run, payload or worker
  long long messages_malformed = 0;
};

class FarmWorker {
 public:
  FarmWorker(lcm::LCM& lcm, WorkerSettings settings);
  ~FarmWorker();  // finishes the running episodes, drops queued jobs
  FarmWorker(const FarmWorker&) = delete;
  FarmWorker& operator=(const FarmWorker&) = delete;

  // Heartbeats, chunk requests and finished results; call after every
  // HandleFor. Returns log lines for main to print.
  std::vector<std::string> Poll();

  const std::string& id() const { return settings_.id; }
  WorkerCounters counters() const;

 private:
  // Handlers run on LCM's thread while episodes run on the pool: lock.
  void CountMalformed();
  using Clock = std::chrono::steady_clock;
  struct Task {
    std::shared_ptr<const Problem> problem;
    std::string run_id, hash;
    std::int64_t job_id = 0;
    std::int32_t generation = 0, index = 0;
    Genome genome;
  };

  void OnRun(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnChunk(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnJob(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void RequestMissing();
  void Work();

  lcm::LCM& lcm_;
  WorkerSettings settings_;
  std::vector<lcm::Subscription*> subscriptions_;
  std::string host_;

  // Run being followed (main thread only).
  std::string run_id_, hash_;
  Clock::time_point last_announce_;
  ChunkAssembler assembler_;
  bool fetching_ = false;
  std::shared_ptr<const Problem> problem_;  // set once decoded and checked
  std::string bad_hash_;  // a payload that did not decode: not retried
  Clock::time_point last_heartbeat_, last_request_;
  std::vector<std::string> log_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Task> queue_;
  std::set<std::int64_t> held_;
  std::vector<opt_result_t> finished_;
  bool quit_ = false;
  WorkerCounters counters_;
  std::vector<std::thread> threads_;
};

}  // namespace mrsim
