// A simulated farm for the cores' tests: one FarmMasterCore and any number
// of FarmWorkerCores on a fake clock, joined by a simulated network with
// per-message delay, jitter and loss, partitions and deaf workers. No
// sockets, no threads, no sleeps: thousands of simulated seconds run in
// milliseconds.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <queue>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "optimizer/episode/episode.h"
#include "optimizer/farm/farm_master_core.h"
#include "optimizer/farm/farm_worker_core.h"
#include "optimizer/search/random.h"

namespace mrsim::testing {

// The fitness a simulated episode reports: a function of the genome only.
inline double SimFitness(const Genome& g) {
  double sum = 0;
  for (double v : g) sum += std::sin(3 * v) + v;
  return sum;
}

struct SimNetwork {
  double delay = 0.001;  // s, one way
  double jitter = 0.0;   // s, uniform +-
  double loss = 0.0;     // probability a message is lost
};

class SimFarm {
 public:
  using Message = std::variant<opt_run_t, opt_chunk_t, opt_chunk_request_t,
                               opt_heartbeat_t, opt_job_t, opt_result_t>;

  SimFarm(std::string payload, FarmSettings settings, SimNetwork net,
          std::uint64_t seed = 1)
      : payload_(std::move(payload)),
        settings_(std::move(settings)),
        net_(net),
        random_(seed) {
    StartMaster("run-1", 1000);
  }

  // A new master process (a restart): another run id, a later start.
  void StartMaster(const std::string& run_id, std::int64_t started) {
    master_ =
        std::make_unique<FarmMasterCore>(payload_, run_id, started, settings_);
  }

  void AddWorker(const std::string& id, double episode, int threads = 1) {
    WorkerSettings s;
    s.id = id;
    s.threads = threads;
    Node n;
    n.core = std::make_unique<FarmWorkerCore>(
        s, "simhost", 1, [](const std::string&, const std::string&) {
          return std::make_shared<const Problem>();
        });
    n.episode = episode;
    workers_[id] = std::move(n);
  }
  // A worker as mrsim-worker is one: it decodes the payload with
  // DecodeProblem and runs the real episode (RunEpisode, as
  // FarmWorker::Run does), reporting after `episode` simulated seconds.
  void AddRealWorker(const std::string& id, double episode) {
    WorkerSettings s;
    s.id = id;
    Node n;
    n.core = std::make_unique<FarmWorkerCore>(s, "simhost", 1);
    n.episode = episode;
    n.real = true;
    workers_[id] = std::move(n);
  }
  void KillWorker(const std::string& id) { workers_.erase(id); }
  // Cut a worker off both ways (a partition) or only from what the master
  // multicasts (a lost group membership: it still beats; a re-join heals).
  void SetPartitioned(const std::string& id, bool on) {
    workers_.at(id).partitioned = on;
  }
  void SetDeaf(const std::string& id, bool on) { workers_.at(id).deaf = on; }
  // A worker that lies: every fitness it reports is off by one.
  void SetLiar(const std::string& id, bool on) { workers_.at(id).lies = on; }
  void SetNetwork(SimNetwork net) { net_ = net; }
  // Drop the next `n` results a worker sends.
  void DropResults(const std::string& id, int n) {
    workers_.at(id).drop_results = n;
  }

  FarmMasterCore& master() { return *master_; }
  FarmWorkerCore& worker(const std::string& id) {
    return *workers_.at(id).core;
  }
  double now() const { return now_; }
  long long episodes_run() const { return episodes_run_; }
  long long episodes_run_by(const std::string& id) const {
    auto it = started_by_.find(id);
    return it == started_by_.end() ? 0 : it->second;
  }
  long long jobs_addressed_to(const std::string& id) const {
    auto it = jobs_to_.find(id);
    return it == jobs_to_.end() ? 0 : it->second;
  }
  long long messages_to_master() const { return to_master_; }

  // Runs until `until` (simulated s) or `done` holds; true when done held.
  bool RunUntil(double until, const std::function<bool()>& done = {}) {
    while (now_ < until) {
      if (done && done()) return true;
      Step(std::min(until, NextTime()));
    }
    return done && done();
  }

  // One batch through the master; false when it did not finish in time.
  bool Evaluate(const std::vector<Genome>& batch, double limit,
                std::vector<EvalResult>* out) {
    master_->StartBatch(batch, now_);
    const bool ok =
        RunUntil(now_ + limit, [&] { return master_->batch_done(); });
    if (ok) *out = master_->results();
    return ok;
  }

  // Hooks for a test to act at a simulated time.
  void At(double t, std::function<void()> action) {
    actions_.emplace(t, std::move(action));
  }

 private:
  struct Node {
    std::unique_ptr<FarmWorkerCore> core;
    double episode = 1.0;
    bool partitioned = false;
    bool deaf = false;
    bool lies = false;
    bool real = false;  // AddRealWorker
    int drop_results = 0;
    std::multimap<double, WorkerTask> running;
  };
  struct Event {
    double time;
    long long seq;
    std::string to;  // "" = master
    Message msg;
    bool operator>(const Event& o) const {
      return time != o.time ? time > o.time : seq > o.seq;
    }
  };

  double NextTime() const {
    double t = now_ + 0.05;
    if (!events_.empty()) t = std::min(t, events_.top().time);
    t = std::min(t, master_->next_deadline());
    for (const auto& [id, n] : workers_) {
      t = std::min(t, n.core->next_deadline());
      if (!n.running.empty()) t = std::min(t, n.running.begin()->first);
    }
    if (!actions_.empty()) t = std::min(t, actions_.begin()->first);
    return std::max(t, now_ + 1e-6);
  }

  void Send(const std::string& to, Message msg) {
    if (random_.Uniform(0, 1) < net_.loss) return;
    const double d =
        net_.delay +
        (net_.jitter > 0 ? random_.Uniform(-net_.jitter, net_.jitter) : 0.0);
    events_.push(Event{now_ + std::max(0.0, d), seq_++, to, std::move(msg)});
  }

  void FromMaster(FarmOutbox out) {
    // Multicast: every worker gets its own copy (its own loss and delay).
    for (auto& [id, n] : workers_) {
      if (n.partitioned || n.deaf) continue;
      for (const auto& m : out.runs) Send(id, m);
      for (const auto& m : out.chunks) Send(id, m);
      for (const auto& m : out.jobs) {
        if (m.worker_id != id) continue;
        for (int c = 0; c < out.copies; ++c) Send(id, m);
      }
    }
    for (const auto& m : out.jobs) ++jobs_to_[m.worker_id];
  }

  void FromWorker(Node& n, FarmOutbox out) {
    if (out.rejoin) n.deaf = false;  // re-joining the group heals it
    if (n.partitioned) return;
    for (auto& m : out.heartbeats) Send("", m);
    for (auto& m : out.chunk_requests) Send("", m);
    for (auto& m : out.results) {
      if (n.drop_results > 0) {
        --n.drop_results;  // every copy of it
        continue;
      }
      for (int c = 0; c < out.copies; ++c) Send("", m);
    }
  }

  void Deliver(Event& e) {
    if (e.to.empty()) {
      ++to_master_;
      std::visit(
          [&](auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, opt_heartbeat_t>) {
              master_->OnHeartbeat(m, now_);
            } else if constexpr (std::is_same_v<T, opt_result_t>) {
              master_->OnResult(m, now_);
            } else if constexpr (std::is_same_v<T, opt_chunk_request_t>) {
              master_->OnChunkRequest(m, now_);
            }
          },
          e.msg);
      return;
    }
    auto it = workers_.find(e.to);
    if (it == workers_.end() || it->second.partitioned || it->second.deaf) {
      return;
    }
    FarmWorkerCore& w = *it->second.core;
    std::visit(
        [&](auto& m) {
          using T = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<T, opt_run_t>) {
            w.OnRun(m, now_);
          } else if constexpr (std::is_same_v<T, opt_chunk_t>) {
            w.OnChunk(m, now_);
          } else if constexpr (std::is_same_v<T, opt_job_t>) {
            w.OnJob(m, now_);
          }
        },
        e.msg);
  }

  void Step(double t) {
    now_ = t;
    while (!actions_.empty() && actions_.begin()->first <= now_) {
      auto action = std::move(actions_.begin()->second);
      actions_.erase(actions_.begin());
      action();
    }
    while (!events_.empty() && events_.top().time <= now_) {
      Event e = events_.top();
      events_.pop();
      Deliver(e);
    }
    for (auto& [id, n] : workers_) {
      while (!n.running.empty() && n.running.begin()->first <= now_) {
        const WorkerTask task = n.running.begin()->second;
        n.running.erase(n.running.begin());
        opt_result_t r{};
        r.run_id = task.run_id;
        r.scenario_hash = task.hash;
        r.worker_id = id;
        r.job_id = task.job_id;
        r.generation = task.generation;
        r.index = task.index;
        if (n.real) {
          const EvalResult e = RunEpisode(*task.problem, task.genome);
          r.fitness = e.fitness;
          r.distance = e.distance;
          r.speed = e.speed;
          r.energy = e.energy;
          r.drift = e.drift;
          r.fell = e.fell;
          r.failed = e.failed;
          if (e.failed) r.error = e.error;
        } else {
          r.fitness = r.distance = SimFitness(task.genome);
        }
        if (n.lies) r.fitness += 1.0;
        r.eval_seconds = n.episode;
        n.core->OnEpisodeDone(r, now_);
      }
      for (WorkerTask& task : n.core->TakeTasks()) {
        ++episodes_run_;
        ++started_by_[id];
        n.running.emplace(now_ + n.episode, std::move(task));
      }
      FromWorker(n, n.core->Tick(now_));
    }
    FromMaster(master_->Tick(now_));
  }

  std::string payload_;
  FarmSettings settings_;
  SimNetwork net_;
  Random random_;
  std::unique_ptr<FarmMasterCore> master_;
  std::map<std::string, Node> workers_;
  std::priority_queue<Event, std::vector<Event>, std::greater<Event>> events_;
  std::multimap<double, std::function<void()>> actions_;
  long long seq_ = 0;
  double now_ = 0;
  long long episodes_run_ = 0;
  long long to_master_ = 0;
  std::map<std::string, long long> started_by_, jobs_to_;
};

}  // namespace mrsim::testing
