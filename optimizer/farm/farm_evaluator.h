// The master's side of the farm: a BatchEvaluator that hands a generation
// out as jobs to mrsim-worker processes over LCM and collects the results.
//
// It announces the run (run id, payload hash, chunk count), serves payload
// chunks on request, tracks workers by their heartbeats and keeps a few
// jobs queued on each ready worker. A job not answered by its deadline, or
// held by a worker that stopped beating, goes to another worker (the same
// one if none is free); the first answer wins, late and duplicate answers
// and messages of other runs or payloads are counted and dropped. Results
// are a function of the genome only, so faults never change them.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "optimizer/batch_evaluator.h"

namespace mrsim {

struct FarmSettings {
  std::string prefix = "MRSIM_OPT";
  // A job is re-sent when not answered this long after it was sent; 0:
  // automatic (10 s, then 3 x the slowest episode seen x the jobs a worker
  // holds, plus 2 s).
  double job_timeout = 0.0;
  double worker_timeout = 2.0;    // s without heartbeat: the worker is gone
  int extra_jobs_per_worker = 1;  // queued beyond its slots (hides latency)
  double announce_period = 0.5;   // s
  int chunk_size = 48000;         // payload bytes per chunk (<= 60000)
  std::function<bool()> stop;     // polled; true abandons the batch
  std::function<void(const std::string&)> log;  // events (worker joined...)
};

struct FarmCounters {
  long long jobs_sent = 0;
  long long jobs_resent = 0;
  long long results_accepted = 0;
  long long results_ignored = 0;  // late, duplicate, other run or payload
  long long messages_malformed = 0;
  long long chunks_sent = 0;
};

class FarmEvaluator : public BatchEvaluator {
 public:
  // `payload` is EncodeProblem's output; `run_id` tells this master's
  // messages apart from any other's (a fresh one per process).
  FarmEvaluator(lcm::LCM& lcm, std::string payload, std::string run_id,
                FarmSettings settings);
  ~FarmEvaluator() override;
  FarmEvaluator(const FarmEvaluator&) = delete;
  FarmEvaluator& operator=(const FarmEvaluator&) = delete;

  std::vector<EvalResult> Evaluate(const std::vector<Genome>& batch) override;
  int workers_alive() const override;

  const std::string& scenario_hash() const { return hash_; }
  const FarmCounters& counters() const { return counters_; }
  // Sum of the workers' reported episode wall times (s), for overhead.
  double episode_seconds() const { return episode_seconds_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Worker {
    std::string id;
    std::string host;
    bool ready = false;  // holds our payload
    int slots = 1;
    Clock::time_point last_seen;
    std::set<std::int64_t> held;  // job ids it reported holding
    Clock::time_point held_stamp;
  };
  struct Job {
    Genome genome;
    bool done = false;
    bool pending = true;  // waiting to be (re)sent
    std::string worker;   // latest assignee
    std::set<std::string> tried;
    Clock::time_point sent;
  };

  void OnHeartbeat(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnResult(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnChunkRequest(const lcm::ReceiveBuffer* rbuf,
                      const std::string& channel);
  void Announce();
  void Maintain(Clock::time_point now);
  void Dispatch(Clock::time_point now);
  void Send(std::int64_t job_id, Job& job, const std::string& worker,
            Clock::time_point now);
  double JobTimeout() const;
  int Outstanding(const std::string& worker) const;
  void Log(const std::string& text) const;

  lcm::LCM& lcm_;
  std::string payload_;
  std::string run_id_;
  std::string hash_;
  FarmSettings settings_;
  std::vector<std::string> chunks_;
  // When each chunk last went out: workers asking together get one copy
  // (it is multicast to all of them).
  std::vector<Clock::time_point> chunk_sent_;
  std::vector<lcm::Subscription*> subscriptions_;

  std::map<std::string, Worker> workers_;
  std::map<std::int64_t, Job> jobs_;  // of the current batch
  std::vector<EvalResult> results_;
  std::int64_t batch_ = 0;
  int gene_count_ = 0;
  Clock::time_point last_announce_;
  double slowest_episode_ = 0.0;
  double episode_seconds_ = 0.0;
  FarmCounters counters_;
};

}  // namespace mrsim
