#include "optimizer/farm/farm_worker.h"

#include <fmt/format.h>
#include <pthread.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "optimizer/episode/episode.h"

namespace mrsim {
namespace {

std::string HostName() {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  return host;
}

// The ids of a process's workers: --id (default host-pid), and -k after
// it for each of several fake workers.
std::vector<std::string> CoreIds(const WorkerSettings& settings, int count) {
  const std::string id =
      settings.id.empty()
          ? fmt::format("{}-{}", HostName(), static_cast<int>(getpid()))
          : settings.id;
  count = std::max(1, count);
  if (count == 1) return {id};
  std::vector<std::string> ids;
  for (int k = 0; k < count; ++k) ids.push_back(fmt::format("{}-{}", id, k));
  return ids;
}

FarmLink::Handlers WithJobWorkers(FarmLink::Handlers h,
                                  std::vector<std::string> ids) {
  h.job_workers = std::move(ids);
  return h;
}

}  // namespace

// The link first: a bad URL throws before any pool thread exists (a
// constructor that throws leaves running threads to std::terminate).
FarmWorker::FarmWorker(const std::string& lcm_url, WorkerSettings settings,
                       int count) {
  link_ = std::make_unique<FarmLink>(
      lcm_url, settings.prefix,
      WithJobWorkers(MakeHandlers(), CoreIds(settings, count)), settings.auth);
  link_->SetWake(&done_fd_);
  Build(settings, count);
}

FarmWorker::FarmWorker(SignedLcm& lcm, WorkerSettings settings, int count) {
  link_ = std::make_unique<FarmLink>(
      lcm, settings.prefix,
      WithJobWorkers(MakeHandlers(), CoreIds(settings, count)));
  link_->SetWake(&done_fd_);
  Build(settings, count);
}

void FarmWorker::Build(WorkerSettings settings, int count) {
  const std::string host = HostName();
  const int pid = static_cast<int>(getpid());
  if (settings.id.empty()) settings.id = fmt::format("{}-{}", host, pid);
  if (settings.threads < 1) settings.threads = 1;
  id_ = settings.id;
  fake_episode_ = settings.fake_episode;
  FarmWorkerCore::Decoder decode;
  if (fake_episode_ > 0) {
    // Protocol only: the payload's hash was checked; nothing to decode.
    decode = [](const std::string&, const std::string&) {
      return std::make_shared<const Problem>();
    };
  }
  count = std::max(1, count);
  dirty_.assign(static_cast<size_t>(count), 1);
  for (int k = 0; k < count; ++k) {
    WorkerSettings s = settings;
    if (count > 1) s.id = fmt::format("{}-{}", settings.id, k);
    cores_.push_back(std::make_unique<FarmWorkerCore>(s, host, pid, decode));
    by_id_[cores_.back()->id()] = cores_.size() - 1;
  }
  if (fake_episode_ <= 0) {
    for (int t = 0; t < settings.threads; ++t) {
      threads_.emplace_back([this] { Work(); });
    }
  }
}

FarmWorker::~FarmWorker() {
  abandon_ = true;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
    pool_queue_.clear();
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

FarmWorkerCore* FarmWorker::Find(const std::string& id) {
  auto it = by_id_.find(id);
  if (it == by_id_.end()) return nullptr;
  dirty_[it->second] = 1;
  return cores_[it->second].get();
}

FarmLink::Handlers FarmWorker::MakeHandlers() {
  FarmLink::Handlers h;
  h.run = [this](const opt_run_t& m) {
    const double now = FarmLink::Now();
    for (auto& c : cores_) c->OnRun(m, now);
    dirty_.assign(cores_.size(), 1);
  };
  h.chunk = [this](const opt_chunk_t& m) {
    const double now = FarmLink::Now();
    for (auto& c : cores_) c->OnChunk(m, now);
    dirty_.assign(cores_.size(), 1);
  };
  h.job = [this](const opt_job_t& m) {
    if (FarmWorkerCore* c = Find(m.worker_id)) {
      c->OnJob(m, FarmLink::Now());
    } else {
      ++jobs_for_others_;  // another worker's, on our shard (or on udpm)
    }
  };
  h.malformed = [this] { cores_.front()->CountMalformed(); };
  return h;
}

WorkerCounters FarmWorker::counters() const {
  WorkerCounters sum;
  sum.messages_ignored = jobs_for_others_;
  for (const auto& c : cores_) {
    const WorkerCounters& k = c->counters();
    sum.jobs_done += k.jobs_done;
    sum.messages_ignored += k.messages_ignored;
    sum.messages_malformed += k.messages_malformed;
    sum.results_resent += k.results_resent;
    sum.rejoins += k.rejoins;
    sum.heartbeats_sent += k.heartbeats_sent;
  }
  return sum;
}

opt_result_t FarmWorker::Run(const WorkerTask& task, const std::string& worker,
                             double fake_episode, EpisodePhysicsPool* physics,
                             const std::function<bool()>& stop) {
  opt_result_t r{};
  r.run_id = task.run_id;
  r.scenario_hash = task.hash;
  r.worker_id = worker;
  r.job_id = task.job_id;
  r.generation = task.generation;
  r.index = task.index;
  if (fake_episode > 0) {
    // A smooth function of the genome, the same on every worker.
    double sum = 0;
    for (double g : task.genome) sum += std::sin(g) * g;
    r.fitness = r.distance = sum;
    r.eval_seconds = fake_episode;
    return r;
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    task.problem->genome.Check(task.genome);
    const EvalResult e = RunEpisode(*task.problem, task.genome, stop, physics);
    r.fitness = e.fitness;
    r.distance = e.distance;
    r.speed = e.speed;
    r.energy = e.energy;
    r.drift = e.drift;
    r.fell = e.fell;
    r.failed = e.failed;
    // Why it failed travels in `error` beside failed = true (a failed
    // evaluation, not a job that could not run: farm_master_core.cc).
    if (e.failed) r.error = e.error;
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.eval_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
          .count();
  return r;
}

void FarmWorker::Work() {
  pthread_setname_np(pthread_self(), kEpisodeThreadName);
  for (;;) {
    std::pair<std::string, WorkerTask> item;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] {
        return quit_ || !pool_queue_.empty() || !warm_queue_.empty();
      });
      if (quit_) return;
      if (pool_queue_.empty()) {
        const std::shared_ptr<const Problem> problem = warm_queue_.front();
        warm_queue_.pop_front();
        lock.unlock();
        PrepareEpisode(*problem, &physics_);
        continue;
      }
      item = std::move(pool_queue_.front());
      pool_queue_.pop_front();
    }
    opt_result_t r = Run(item.second, item.first, 0, &physics_,
                         [this] { return abandon_.load(); });
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_.push_back(std::move(r));
    }
    done_fd_.Signal();
  }
}

std::vector<std::string> FarmWorker::Poll(int timeout_ms) {
  if (!fake_running_.empty()) {
    // Wake for the first fake episode's end, not a whole timeout later.
    const double until = fake_running_.begin()->first - FarmLink::Now();
    timeout_ms =
        std::clamp(static_cast<int>(std::ceil(until * 1000)), 0, timeout_ms);
  }
  link_->Handle(timeout_ms);
  const double now = FarmLink::Now();
  std::vector<opt_result_t> done;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done.swap(finished_);
    // A job handed out ahead whose core has followed another run since.
    for (auto it = pool_queue_.begin(); it != pool_queue_.end();) {
      FarmWorkerCore& core = *cores_[by_id_.at(it->first)];
      if (it->second.run_id == core.run_id()) {
        ++it;
        continue;
      }
      core.Forget(it->second.job_id);
      it = pool_queue_.erase(it);
    }
  }
  while (!fake_running_.empty() && fake_running_.begin()->first <= now) {
    done.push_back(std::move(fake_running_.begin()->second));
    fake_running_.erase(fake_running_.begin());
  }
  for (opt_result_t& r : done) {
    if (FarmWorkerCore* c = Find(r.worker_id)) c->OnEpisodeDone(r, now);
  }
  FarmOutbox all;
  bool rejoin = false;
  for (size_t k = 0; k < cores_.size(); ++k) {
    FarmWorkerCore* c = cores_[k].get();
    if (!dirty_[k] && c->next_deadline() > now && now - c->last_tick() < 0.5) {
      continue;
    }
    dirty_[k] = 0;
    // The pool holds one job beyond its threads: a thread that ends an
    // episode takes it at once. Waiting for this loop to hand it over cost
    // two thread wake-ups per episode, and at a CPU cap a wake-up can wait
    // for the next quota period. Fake episodes run on this loop's clock.
    for (WorkerTask& t : c->TakeTasks(fake_episode_ > 0 ? 0 : 1)) {
      if (fake_episode_ > 0) {
        fake_running_.emplace(now + fake_episode_,
                              Run(t, c->id(), fake_episode_, &physics_));
      } else {
        std::lock_guard<std::mutex> lock(mutex_);
        pool_queue_.emplace_back(c->id(), std::move(t));
        wake_.notify_one();
      }
    }
    FarmOutbox out = c->Tick(now);
    rejoin = rejoin || out.rejoin;
    all.copies = std::max(all.copies, out.copies);
    const auto move = [](auto& from, auto& to) {
      for (auto& m : from) to.push_back(std::move(m));
    };
    move(out.chunk_requests, all.chunk_requests);
    move(out.heartbeats, all.heartbeats);
    move(out.results, all.results);
    for (const std::string& line : c->TakeLog()) {
      log_.push_back(cores_.size() > 1 ? c->id() + ": " + line : line);
    }
  }
  if (fake_episode_ <= 0 && cores_.front()->problem() != warmed_) {
    warmed_ = cores_.front()->problem();
    if (warmed_) {
      std::lock_guard<std::mutex> lock(mutex_);
      warm_queue_.push_back(warmed_);
      wake_.notify_one();
    }
  }
  all.rejoin = rejoin;
  link_->Publish(all);
  for (const std::string& line : link_->TakeLog()) log_.push_back(line);
  std::vector<std::string> lines;
  lines.swap(log_);
  return lines;
}

}  // namespace mrsim
