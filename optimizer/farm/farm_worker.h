// mrsim-worker's node: one or more FarmWorkerCores (more than one only for
// protocol-only fake workers, which let one process stand in for hundreds
// of hosts), a FarmLink for LCM and the clock, and a thread pool running
// the episodes the cores hand out.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"
#include "optimizer/episode/episode_physics_pool.h"
#include "optimizer/farm/farm_link.h"
#include "optimizer/farm/farm_worker_core.h"

namespace mrsim {

class FarmWorker {
 public:
  // The name of the threads that run episodes (`top -H`, /proc/PID/task):
  // the farm benchmark tells their CPU from the LCM threads' by it.
  static constexpr const char* kEpisodeThreadName = "episode";

  // `count` > 1 (fake workers only) runs that many workers named
  // <id>-0 ... <id>-(count-1).
  FarmWorker(const std::string& lcm_url, WorkerSettings settings,
             int count = 1);
  FarmWorker(SignedLcm& lcm, WorkerSettings settings, int count = 1);
  ~FarmWorker();  // abandons the running episodes, drops queued jobs
  FarmWorker(const FarmWorker&) = delete;
  FarmWorker& operator=(const FarmWorker&) = delete;

  // Handles LCM for up to timeout_ms, then beats, requests chunks, starts
  // jobs and sends results. Returns log lines for main to print.
  std::vector<std::string> Poll(int timeout_ms = 20);

  const std::string& id() const { return id_; }
  WorkerCounters counters() const;

 private:
  void Build(WorkerSettings settings, int count);
  FarmLink::Handlers MakeHandlers();
  FarmWorkerCore* Find(const std::string& id);
  void Work();
  static opt_result_t Run(const WorkerTask& task, const std::string& worker,
                          double fake_episode, EpisodePhysicsPool* physics,
                          const std::function<bool()>& stop = {});

  std::string id_;
  // Jobs heard for workers of another process (a shared job shard, or
  // udpm), counted as messages ignored.
  long long jobs_for_others_ = 0;
  double fake_episode_ = 0;
  std::vector<std::unique_ptr<FarmWorkerCore>> cores_;
  std::unordered_map<std::string, size_t> by_id_;
  // Cores that heard something since their last Tick (the others are
  // ticked only when their own deadline comes: hundreds of fake workers
  // in one process cost nothing while idle).
  std::vector<char> dirty_;
  std::unique_ptr<FarmLink> link_;
  std::vector<std::string> log_;

  // Fake episodes: (end time, result), sorted by end time.
  std::multimap<double, opt_result_t> fake_running_;

  // Readable when an episode has finished: wakes Poll's wait (an eventfd).
  WakeFd done_fd_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::pair<std::string, WorkerTask>> pool_queue_;
  // Problems whose simulation a pool thread builds while no job waits, so
  // the run's first episode on this worker does not pay the build (about
  // a 4 s episode: on a slow host the whole first generation waited).
  std::deque<std::shared_ptr<const Problem>> warm_queue_;
  std::shared_ptr<const Problem> warmed_;  // the last one queued
  std::vector<opt_result_t> finished_;
  // The simulations this worker's episode threads share (one per episode
  // they run at once, reset for the next episode of the same body).
  EpisodePhysicsPool physics_;
  bool quit_ = false;
  // Set on destruction: running episodes are abandoned (their results
  // would never be sent), so a stopped worker exits at once.
  std::atomic<bool> abandon_{false};
  std::vector<std::thread> threads_;
};

}  // namespace mrsim
