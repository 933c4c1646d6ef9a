#include "optimizer/farm/farm_evaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/wall_time.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/opt_chunk_request_t.hpp"
#include "mrsim/opt_chunk_t.hpp"
#include "mrsim/opt_heartbeat_t.hpp"
#include "mrsim/opt_job_t.hpp"
#include "mrsim/opt_result_t.hpp"
#include "mrsim/opt_run_t.hpp"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/payload_chunks.h"
#include "optimizer/hash.h"

namespace mrsim {
namespace {

constexpr int kJobIdShift = 24;  // job id = batch << 24 | index

}  // namespace

FarmEvaluator::FarmEvaluator(lcm::LCM& lcm, std::string payload,
                             std::string run_id, FarmSettings settings)
    : lcm_(lcm),
      payload_(std::move(payload)),
      run_id_(std::move(run_id)),
      hash_(HashHex(Fnv1a64(payload_))),
      settings_(std::move(settings)),
      chunks_(SplitPayload(payload_, static_cast<size_t>(std::clamp(
                                         settings_.chunk_size, 1, 60000)))) {
  chunk_sent_.assign(chunks_.size(), Clock::time_point{});
  const FarmChannels ch(settings_.prefix);
  subscriptions_.push_back(
      lcm_.subscribe(ch.heartbeat, &FarmEvaluator::OnHeartbeat, this));
  subscriptions_.push_back(
      lcm_.subscribe(ch.result, &FarmEvaluator::OnResult, this));
  subscriptions_.push_back(
      lcm_.subscribe(ch.chunk_request, &FarmEvaluator::OnChunkRequest, this));
  Announce();
}

FarmEvaluator::~FarmEvaluator() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

void FarmEvaluator::Log(const std::string& text) const {
  if (settings_.log) settings_.log(text);
}

int FarmEvaluator::workers_alive() const {
  return static_cast<int>(workers_.size());
}

void FarmEvaluator::Announce() {
  opt_run_t msg;
  msg.utime = WallMicros();
  msg.run_id = run_id_;
  msg.scenario_hash = hash_;
  msg.payload_size = static_cast<std::int64_t>(payload_.size());
  msg.chunk_count = static_cast<int32_t>(chunks_.size());
  msg.chunk_size = static_cast<int32_t>(chunks_.front().size());
  lcm_.publish(FarmChannels(settings_.prefix).run, &msg);
  last_announce_ = Clock::now();
}

void FarmEvaluator::OnHeartbeat(const lcm::ReceiveBuffer* rbuf,
                                const std::string&) {
  try {
    opt_heartbeat_t msg;
    if (!DecodeMessage(rbuf, &msg) || msg.worker_id.empty() || msg.slots < 1 ||
        msg.job_count < 0) {
      ++counters_.messages_malformed;
      return;
    }
    const auto now = Clock::now();
    auto [it, fresh] = workers_.try_emplace(msg.worker_id);
    Worker& w = it->second;
    if (fresh) {
      w.id = msg.worker_id;
      w.host = msg.host;
      Log(fmt::format("worker {} ({}) joined", w.id, w.host));
    }
    w.last_seen = now;
    w.slots = std::min(msg.slots, 64);
    const bool ready = msg.run_id == run_id_ && msg.scenario_hash == hash_;
    if (ready && !w.ready) Log(fmt::format("worker {} is ready", w.id));
    w.ready = ready;
    w.held.clear();
    for (std::int64_t id : msg.jobs) w.held.insert(id);
    w.held_stamp = now;
  } catch (...) {
    ++counters_.messages_malformed;
  }
}

void FarmEvaluator::OnResult(const lcm::ReceiveBuffer* rbuf,
                             const std::string&) {
  try {
    opt_result_t msg;
    if (!DecodeMessage(rbuf, &msg)) {
      ++counters_.messages_malformed;
      return;
    }
    if (msg.run_id != run_id_ || msg.scenario_hash != hash_) {
      ++counters_.results_ignored;
      return;
    }
    auto it = jobs_.find(msg.job_id);
    if (it == jobs_.end() || it->second.done) {
      ++counters_.results_ignored;  // late (older batch) or duplicate
      return;
    }
    if (!msg.error.empty()) {
      Log(fmt::format("worker {} could not run job {}: {}", msg.worker_id,
                      msg.job_id, msg.error));
      it->second.pending = true;
      it->second.tried.insert(msg.worker_id);
      return;
    }
    for (double v : {msg.fitness, msg.distance, msg.speed, msg.energy,
                     msg.drift, msg.fell}) {
      if (std::isnan(v)) {
        ++counters_.messages_malformed;
        return;
      }
    }
    EvalResult r;
    r.fitness = msg.fitness;
    r.distance = msg.distance;
    r.speed = msg.speed;
    r.energy = msg.energy;
    r.drift = msg.drift;
    r.fell = msg.fell;
    r.failed = msg.failed;
    results_[static_cast<size_t>(msg.job_id & ((1 << kJobIdShift) - 1))] = r;
    it->second.done = true;
    it->second.pending = false;
    ++counters_.results_accepted;
    if (std::isfinite(msg.eval_seconds) && msg.eval_seconds > 0) {
      slowest_episode_ = std::max(slowest_episode_, msg.eval_seconds);
      episode_seconds_ += msg.eval_seconds;
    }
  } catch (...) {
    ++counters_.messages_malformed;
  }
}

void FarmEvaluator::OnChunkRequest(const lcm::ReceiveBuffer* rbuf,
                                   const std::string&) {
  try {
    opt_chunk_request_t msg;
    if (!DecodeMessage(rbuf, &msg)) {
      ++counters_.messages_malformed;
      return;
    }
    if (msg.run_id != run_id_ || msg.scenario_hash != hash_) return;
    const std::string channel = FarmChannels(settings_.prefix).chunk;
    for (int index : msg.missing) {
      if (index < 0 || index >= static_cast<int>(chunks_.size())) {
        ++counters_.messages_malformed;
        continue;
      }
      const auto now = Clock::now();
      if (now - chunk_sent_[index] < std::chrono::milliseconds(100)) continue;
      chunk_sent_[index] = now;
      opt_chunk_t chunk;
      chunk.utime = WallMicros();
      chunk.run_id = run_id_;
      chunk.scenario_hash = hash_;
      chunk.index = index;
      chunk.count = static_cast<int32_t>(chunks_.size());
      chunk.data.assign(chunks_[index].begin(), chunks_[index].end());
      chunk.size = static_cast<int32_t>(chunk.data.size());
      lcm_.publish(channel, &chunk);
      ++counters_.chunks_sent;
    }
  } catch (...) {
    ++counters_.messages_malformed;
  }
}

double FarmEvaluator::JobTimeout() const {
  if (settings_.job_timeout > 0) return settings_.job_timeout;
  if (slowest_episode_ <= 0) return 10.0;
  return 2.0 + 3.0 * slowest_episode_ * (1 + settings_.extra_jobs_per_worker);
}

int FarmEvaluator::Outstanding(const std::string& worker) const {
  int n = 0;
  for (const auto& [id, job] : jobs_) {
    if (!job.done && !job.pending && job.worker == worker) ++n;
  }
  return n;
}

void FarmEvaluator::Send(std::int64_t job_id, Job& job,
                         const std::string& worker, Clock::time_point now) {
  opt_job_t msg;
  msg.utime = WallMicros();
  msg.run_id = run_id_;
  msg.scenario_hash = hash_;
  msg.worker_id = worker;
  msg.job_id = job_id;
  msg.generation = static_cast<int32_t>(batch_);
  msg.index = static_cast<int32_t>(job_id & ((1 << kJobIdShift) - 1));
  msg.gene_count = static_cast<int32_t>(job.genome.size());
  msg.genome = job.genome;
  lcm_.publish(FarmChannels(settings_.prefix).job, &msg);
  if (!job.tried.empty()) ++counters_.jobs_resent;
  ++counters_.jobs_sent;
  job.pending = false;
  job.worker = worker;
  job.tried.insert(worker);
  job.sent = now;
}

void FarmEvaluator::Maintain(Clock::time_point now) {
  const auto seconds = [](Clock::duration d) {
    return std::chrono::duration<double>(d).count();
  };
  for (auto it = workers_.begin(); it != workers_.end();) {
    if (seconds(now - it->second.last_seen) > settings_.worker_timeout) {
      int lost = 0;
      for (auto& [id, job] : jobs_) {
        if (!job.done && !job.pending && job.worker == it->first) {
          job.pending = true;
          ++lost;
        }
      }
      Log(fmt::format("worker {} is gone{}", it->first,
                      lost ? fmt::format("; {} job(s) re-queued", lost) : ""));
      it = workers_.erase(it);
    } else {
      ++it;
    }
  }
  const double timeout = JobTimeout();
  for (auto& [id, job] : jobs_) {
    if (job.done || job.pending) continue;
    if (seconds(now - job.sent) > timeout) {
      Log(fmt::format("job {} unanswered after {:.1f} s; re-queued", id,
                      timeout));
      job.pending = true;
      continue;
    }
    // A worker that reported its jobs well after we sent this one and did
    // not list it never got it (or its answer was lost).
    auto w = workers_.find(job.worker);
    if (w != workers_.end() && w->second.ready &&
        seconds(w->second.held_stamp - job.sent) > 0.5 &&
        !w->second.held.count(id)) {
      job.pending = true;
    }
  }
}

void FarmEvaluator::Dispatch(Clock::time_point now) {
  // Ready workers, least loaded first (ties: by id, for a stable order).
  std::vector<std::pair<int, std::string>> order;
  for (const auto& [id, w] : workers_) {
    if (w.ready) order.emplace_back(Outstanding(id) - w.slots, id);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [load, id] : order) {
    const Worker& w = workers_.at(id);
    int room = w.slots + settings_.extra_jobs_per_worker - Outstanding(id);
    while (room > 0) {
      // Prefer a job this worker has not had (a re-send goes elsewhere).
      Job* pick = nullptr;
      std::int64_t pick_id = 0;
      for (auto& [job_id, job] : jobs_) {
        if (job.done || !job.pending) continue;
        if (!job.tried.count(id)) {
          pick = &job;
          pick_id = job_id;
          break;
        }
        if (!pick) {
          pick = &job;
          pick_id = job_id;
        }
      }
      if (!pick) return;
      // A job already tried here waits for another worker if one has room.
      if (pick->tried.count(id)) {
        bool other_free = false;
        for (const auto& [oid, ow] : workers_) {
          if (oid != id && ow.ready &&
              Outstanding(oid) < ow.slots + settings_.extra_jobs_per_worker) {
            other_free = true;
          }
        }
        if (other_free) break;
      }
      Send(pick_id, *pick, id, now);
      --room;
    }
  }
}

std::vector<EvalResult> FarmEvaluator::Evaluate(
    const std::vector<Genome>& batch) {
  ++batch_;
  jobs_.clear();
  results_.assign(batch.size(), EvalResult{});
  if (batch.size() >= (1u << kJobIdShift)) {
    throw std::invalid_argument("farm: batch too large");
  }
  for (size_t i = 0; i < batch.size(); ++i) {
    Job job;
    job.genome = batch[i];
    jobs_[(batch_ << kJobIdShift) | static_cast<std::int64_t>(i)] = job;
  }
  size_t remaining = batch.size();
  auto last_wait_log = Clock::now();
  while (remaining > 0) {
    HandleFor(lcm_, 5);
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_announce_).count() >=
        settings_.announce_period) {
      Announce();
    }
    Maintain(now);
    Dispatch(now);
    remaining = 0;
    for (const auto& [id, job] : jobs_) remaining += job.done ? 0 : 1;
    if (settings_.stop && settings_.stop()) {
      throw EvaluationInterrupted("farm evaluation interrupted");
    }
    bool any_ready = false;
    for (const auto& [id, w] : workers_) any_ready = any_ready || w.ready;
    if (!any_ready &&
        std::chrono::duration<double>(now - last_wait_log).count() > 5.0) {
      Log(fmt::format("waiting for workers on {}_* ({} heard, none ready)",
                      settings_.prefix, workers_.size()));
      last_wait_log = now;
    }
  }
  return results_;
}

}  // namespace mrsim
