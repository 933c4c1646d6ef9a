#include "optimizer/farm/farm_master_core.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/hash.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/payload_chunks.h"

namespace mrsim {
namespace {

constexpr int kJobIdShift = 24;  // job id = batch << 24 | index
constexpr std::int64_t kIndexMask = (std::int64_t{1} << kJobIdShift) - 1;
// s between checks of silence and deadlines: a tenth of a second, or half
// a typical episode when episodes are shorter (a lost datagram is noticed
// in episode time), but no more often than every 20 ms.
constexpr double kMaintainPeriod = 0.1;
constexpr double kMinMaintainPeriod = 0.02;
// A heartbeat received this long after a job went out should list it.
constexpr double kListGrace = 0.5;

}  // namespace

int OnePacketChunkSize(const std::string& prefix, const std::string& run_id,
                       const std::string& hash) {
  opt_chunk_t empty{};
  empty.run_id = run_id;
  empty.scenario_hash = hash;
  empty.size = 0;
  constexpr int kDatagram = 1472;  // 1500 - IPv4 20 - UDP 8
  constexpr int kLcmHeader = 8;    // magic + sequence number
  const int channel = static_cast<int>(FarmChannels(prefix).chunk.size()) + 1;
  return std::max(256, kDatagram - kLcmHeader - channel -
                           static_cast<int>(empty.getEncodedSize()));
}

FarmMasterCore::FarmMasterCore(std::string payload, std::string run_id,
                               std::int64_t started_utime,
                               FarmSettings settings)
    : payload_(std::move(payload)),
      run_id_(std::move(run_id)),
      hash_(HashHex(Fnv1a64(payload_))),
      started_(started_utime),
      settings_(std::move(settings)) {
  int size = settings_.chunk_size;
  if (size <= 0) size = OnePacketChunkSize(settings_.prefix, run_id_, hash_);
  chunks_ =
      SplitPayload(payload_, static_cast<size_t>(std::clamp(size, 1, 60000)));
  chunk_sent_.assign(chunks_.size(), -1e9);
}

void FarmMasterCore::Log(const std::string& text) const {
  if (settings_.log) settings_.log(text);
}

double FarmMasterCore::heartbeat_period() const {
  return std::max(settings_.min_heartbeat_period,
                  static_cast<double>(workers_.size()) /
                      std::max(1.0, settings_.heartbeat_budget));
}

int FarmMasterCore::copies() const {
  if (settings_.copies > 0) return std::min(settings_.copies, 4);
  return workers_.size() <= static_cast<size_t>(settings_.duplicate_up_to) ? 2
                                                                           : 1;
}

double FarmMasterCore::worker_timeout() const {
  return std::max(settings_.worker_timeout, 5 * heartbeat_period() + 1.0);
}

double FarmMasterCore::JobTimeout() const {
  if (settings_.job_timeout > 0) return settings_.job_timeout;
  if (slowest_episode_ <= 0) return 10.0;
  return 2.0 + 3.0 * slowest_episode_ * (1 + settings_.extra_jobs_per_worker);
}

FarmMasterCore::Job* FarmMasterCore::FindJob(std::int64_t job_id) {
  auto it = batches_.find(job_id >> kJobIdShift);
  if (it == batches_.end()) return nullptr;
  const std::int64_t index = job_id & kIndexMask;
  std::vector<Job>& jobs = it->second.jobs;
  if (index < 0 || index >= static_cast<std::int64_t>(jobs.size())) {
    return nullptr;
  }
  return &jobs[static_cast<size_t>(index)];
}

const FarmMasterCore::Batch& FarmMasterCore::OpenAt(std::int64_t id) const {
  auto it = batches_.find(id);
  if (it == batches_.end()) {
    throw std::out_of_range(fmt::format("farm: no open batch {}", id));
  }
  return it->second;
}

void FarmMasterCore::Reindex(Worker& w, double now) {
  if (w.room_load >= 0) room_.erase({w.room_load, w.id});
  w.room_load = -1;
  const int capacity = w.slots + settings_.extra_jobs_per_worker;
  const int load = static_cast<int>(w.assigned.size());
  if (w.ready && now >= w.deaf_until && load < capacity) {
    w.room_load = load;
    room_.emplace(load, w.id);
  }
}

void FarmMasterCore::StartBatch(const std::vector<Genome>& batch, double now) {
  while (!batches_.empty()) CloseBatch(batches_.begin()->first, now);
  OpenBatch(batch);
}

std::int64_t FarmMasterCore::OpenBatch(const std::vector<Genome>& batch) {
  if (batch.size() >= (size_t{1} << kJobIdShift)) {
    throw std::invalid_argument("farm: batch too large");
  }
  const std::int64_t id = ++batch_;
  Batch& b = batches_[id];
  b.genomes = batch;
  b.jobs.assign(batch.size(), Job{});
  b.results.assign(batch.size(), EvalResult{});
  b.remaining = batch.size();
  failure_.clear();
  pending_count_ += batch.size();
  dispatch_due_ = true;
  const double f = std::clamp(settings_.verify, 0.0, 1.0);
  for (size_t i = 0; i < batch.size(); ++i) {
    pending_.push_back((id << kJobIdShift) | static_cast<std::int64_t>(i));
    // Every job whose place in the run crosses a multiple of 1/f: an even
    // spread, the same in every run.
    const double n = static_cast<double>(jobs_opened_++);
    b.jobs[i].verify = f > 0 && std::floor((n + 1) * f) > std::floor(n * f);
  }
  return id;
}

void FarmMasterCore::CloseBatch(std::int64_t id, double now) {
  auto it = batches_.find(id);
  if (it == batches_.end()) return;
  for (const Job& job : it->second.jobs) {
    if (job.pending) --pending_count_;
  }
  batches_.erase(it);
  for (auto& [worker, ids] : results_by_) {
    ids.erase(std::remove_if(
                  ids.begin(), ids.end(),
                  [&](std::int64_t j) { return (j >> kJobIdShift) == id; }),
              ids.end());
  }
  // Its jobs are of no use now: the workers holding them have room again.
  for (auto& [wid, w] : workers_) {
    bool freed = false;
    for (auto j = w.assigned.begin(); j != w.assigned.end();) {
      if ((*j >> kJobIdShift) == id) {
        j = w.assigned.erase(j);
        freed = true;
      } else {
        ++j;
      }
    }
    if (freed) Reindex(w, now);
  }
}

void FarmMasterCore::OnHeartbeat(const opt_heartbeat_t& msg, double now) {
  ++counters_.messages_received;
  ++counters_.heartbeats_received;
  if (msg.worker_id.empty() || msg.slots < 1 || msg.job_count < 0 ||
      msg.done_count < 0) {
    ++counters_.messages_malformed;
    return;
  }
  if (dropped_.count(msg.worker_id) != 0) {  // outvoted: not for this run
    ++counters_.heartbeats_refused;
    return;
  }
  if (msg.build != settings_.build && !settings_.allow_mixed_builds) {
    ++counters_.heartbeats_refused;
    if (refused_.insert(msg.worker_id).second) {
      Log(fmt::format(
          "refused worker {} ({}): its build '{}' is not this master's '{}', "
          "so its results could differ from a local run's; rebuild it alike "
          "or pass --allow-mixed-builds",
          msg.worker_id, msg.host, msg.build, settings_.build));
    }
    return;
  }
  auto [it, fresh] = workers_.try_emplace(msg.worker_id);
  Worker& w = it->second;
  if (fresh) {
    w.id = msg.worker_id;
    Log(fmt::format("worker {} ({}) joined", w.id, msg.host));
  }
  w.last_seen = now;
  w.slots = std::clamp(msg.slots, 1, 64);
  const bool ready = msg.run_id == run_id_ && msg.scenario_hash == hash_;
  if (ready && !w.ready) Log(fmt::format("worker {} is ready", w.id));
  if (!ready && w.ready) {
    // It follows another run now (or lost the payload): nothing it holds
    // of ours will be answered.
    if (!msg.run_id.empty() && msg.run_id != run_id_ && !warned_other_run_) {
      // Workers follow the newest master on a prefix: a second mrsim-opt
      // there takes them all. Said once.
      warned_other_run_ = true;
      Log(fmt::format(
          "worker {} left for another run ({}) on {}_*: another mrsim-opt "
          "uses this prefix; give each run its own --prefix (workers too)",
          w.id, msg.run_id, settings_.prefix));
    }
    std::vector<std::int64_t> lost(w.assigned.begin(), w.assigned.end());
    for (std::int64_t id : lost) Requeue(id, "its worker left the run");
  }
  if (ready != w.ready) ready_count_ += ready ? 1 : -1;
  w.ready = ready;
  if (ready) {
    // One heartbeat's word is not enough to re-send a job: under jitter a
    // heartbeat may overtake the job or its result. A job is taken back
    // after two heartbeats, both well after it went out, list it neither
    // as held nor as recently done.
    std::vector<std::int64_t> assigned(w.assigned.begin(), w.assigned.end());
    for (std::int64_t id : assigned) {
      Job* job = FindJob(id);
      if (!job) continue;
      const bool held =
          std::find(msg.jobs.begin(), msg.jobs.end(), id) != msg.jobs.end();
      const bool done =
          std::find(msg.done.begin(), msg.done.end(), id) != msg.done.end();
      if (held || done) {
        job->unlisted = 0;
        w.misses = 0;
        w.deaf_backoff = 0;
        if (done && job->done_seen < 0) job->done_seen = now;
        continue;
      }
      if (now - job->sent < kListGrace) continue;
      if (++job->unlisted < 2) continue;
      Requeue(id, "never listed by its worker");
      if (++w.misses >= 2) {
        // A worker that never lists what it is sent does not hear us (a
        // lost multicast membership): stop feeding it for a while; it
        // re-joins when it notices the silence.
        w.deaf_backoff = std::clamp(w.deaf_backoff * 2, 2.0, 30.0);
        w.deaf_until = now + w.deaf_backoff;
        Log(fmt::format(
            "worker {} does not list the jobs it was sent; none for {:.0f} s",
            w.id, w.deaf_backoff));
      }
    }
  }
  Reindex(w, now);
}

void FarmMasterCore::OnResult(const opt_result_t& msg, double now) {
  ++counters_.messages_received;
  if (msg.run_id != run_id_ || msg.scenario_hash != hash_) {
    ++counters_.results_ignored;
    return;
  }
  auto wit = workers_.find(msg.worker_id);
  if (wit != workers_.end()) wit->second.last_seen = now;  // a sign of life
  Job* job = FindJob(msg.job_id);
  if (!job || job->done) {
    ++counters_.results_ignored;  // late (older batch) or duplicate
    return;
  }
  // failed with an error: a failed evaluation and why (a controller's
  // message, EvalResult::error); error alone: the job could not run.
  if (!msg.error.empty() && !msg.failed) {
    if (++job->errors >= kMaxJobErrors) {
      if (failure_.empty()) {
        failure_ = fmt::format("workers could not run job {} ({} times): {}",
                               msg.job_id, job->errors, msg.error);
      }
      return;
    }
    Log(fmt::format("worker {} could not run job {}: {}", msg.worker_id,
                    msg.job_id, msg.error));
    if (!job->pending) Requeue(msg.job_id, "error");
    return;
  }
  for (double v : {msg.fitness, msg.distance, msg.speed, msg.energy, msg.drift,
                   msg.fell}) {
    if (std::isnan(v)) {
      ++counters_.messages_malformed;
      return;
    }
  }
  if (dropped_.count(msg.worker_id) != 0) {
    ++counters_.results_ignored;
    return;
  }
  EvalResult r;
  r.fitness = msg.fitness;
  r.distance = msg.distance;
  r.speed = msg.speed;
  r.energy = msg.energy;
  r.drift = msg.drift;
  r.fell = msg.fell;
  r.failed = msg.failed;
  if (msg.failed) r.error = msg.error;
  if (job->verify) {
    Verify(msg.job_id, *job, r, msg.worker_id, msg.eval_seconds, now);
  } else {
    Accept(msg.job_id, *job, r, msg.worker_id, msg.eval_seconds, now);
  }
}

void FarmMasterCore::Accept(std::int64_t job_id, Job& job_ref,
                            const EvalResult& r, const std::string& worker,
                            double eval_seconds, double now) {
  Job* job = &job_ref;
  Batch& batch = batches_.at(job_id >> kJobIdShift);
  batch.results[static_cast<size_t>(job_id & kIndexMask)] = r;
  results_by_[worker].push_back(job_id);
  job->done = true;
  if (job->pending) --pending_count_;
  job->pending = false;  // a stale id in pending_ is skipped
  --batch.remaining;
  ++counters_.results_accepted;
  auto owner = workers_.find(job->worker);
  if (owner != workers_.end() && owner->second.assigned.erase(job_id)) {
    Reindex(owner->second, now);
    Overtaken(owner->second, *job, now);
  }
  if (std::isfinite(eval_seconds) && eval_seconds > 0) {
    typical_episode_ = typical_episode_ <= 0
                           ? eval_seconds
                           : 0.9 * typical_episode_ + 0.1 * eval_seconds;
    slowest_episode_ = std::max(slowest_episode_, eval_seconds);
    episode_seconds_ += eval_seconds;
    double& seconds = batch.worker_seconds[worker];
    seconds += eval_seconds;
    batch.busiest = std::max(batch.busiest, seconds);
  }
  if (batch.remaining == 0) counters_.busiest_worker_seconds += batch.busiest;
}

namespace {

bool Same(const EvalResult& a, const EvalResult& b) {
  return a.fitness == b.fitness && a.distance == b.distance &&
         a.speed == b.speed && a.energy == b.energy && a.drift == b.drift &&
         a.fell == b.fell && a.failed == b.failed;
}

// Opinions on one job before it counts as unsettled (no two agree).
constexpr size_t kMaxOpinions = 4;

}  // namespace

bool FarmMasterCore::Answered(const Job& job, const std::string& worker) {
  for (const auto& o : job.opinions) {
    if (o.first == worker) return true;
  }
  return false;
}

void FarmMasterCore::Verify(std::int64_t job_id, Job& job, const EvalResult& r,
                            const std::string& worker, double eval_seconds,
                            double now) {
  if (Answered(job, worker)) {
    ++counters_.results_ignored;  // a copy, or asked again
    return;
  }
  std::string partner;
  for (const auto& [who, result] : job.opinions) {
    if (dropped_.count(who) == 0 && Same(result, r)) {
      partner = who;
      break;
    }
  }
  job.opinions.emplace_back(worker, r);
  if (!partner.empty()) {
    std::vector<std::string> outvoted;
    for (const auto& [who, result] : job.opinions) {
      if (!Same(result, r) && dropped_.count(who) == 0) outvoted.push_back(who);
    }
    ++counters_.results_verified;
    Accept(job_id, job, r, worker, eval_seconds, now);
    results_by_[partner].push_back(job_id);
    for (const std::string& who : outvoted) {
      Drop(who,
           fmt::format("its result for job {} differs from those of workers "
                       "{} and {}",
                       job_id, partner, worker));
    }
    return;
  }
  if (job.opinions.size() >= kMaxOpinions) {
    if (failure_.empty()) {
      failure_ =
          fmt::format("job {}: {} workers gave {} different results (--verify)",
                      job_id, job.opinions.size(), job.opinions.size());
    }
    return;
  }
  if (job.opinions.size() >= 2) {
    Log(fmt::format("job {}: workers {} and {} disagree; asking a third",
                    job_id, job.opinions[0].first, worker));
  }
  // Free the slots it held and ask a worker that has not run it.
  for (const std::string& who : {worker, job.worker}) {
    auto w = workers_.find(who);
    if (w != workers_.end() && w->second.assigned.erase(job_id)) {
      Reindex(w->second, now);
    }
  }
  if (!job.pending) {
    job.pending = true;
    ++pending_count_;
    pending_.push_front(job_id);
  }
  dispatch_due_ = true;
  job.unlisted = 0;
  job.done_seen = -1;
}

void FarmMasterCore::Drop(const std::string& worker, const std::string& why) {
  if (!dropped_.insert(worker).second) return;
  ++counters_.workers_dropped;
  auto it = workers_.find(worker);
  if (it != workers_.end()) {
    Worker& w = it->second;
    std::vector<std::int64_t> ids(w.assigned.begin(), w.assigned.end());
    for (std::int64_t id : ids) Requeue(id, "its worker was dropped");
    if (w.room_load >= 0) room_.erase({w.room_load, w.id});
    if (w.ready) --ready_count_;
    workers_.erase(it);
  }
  // Its opinions count no more; every result it gave is re-done.
  for (auto& [batch_id, batch] : batches_) {
    for (Job& job : batch.jobs) {
      job.opinions.erase(
          std::remove_if(job.opinions.begin(), job.opinions.end(),
                         [&](const auto& o) { return o.first == worker; }),
          job.opinions.end());
    }
  }
  int redone = 0;
  for (std::int64_t id : results_by_[worker]) {
    Job* job = FindJob(id);
    if (job == nullptr || !job->done) continue;
    Batch& batch = batches_.at(id >> kJobIdShift);
    batch.results[static_cast<size_t>(id & kIndexMask)] = EvalResult{};
    ++batch.remaining;
    job->done = false;
    job->opinions.clear();
    job->pending = true;
    ++pending_count_;
    pending_.push_front(id);
    dispatch_due_ = true;
    ++redone;
  }
  results_by_.erase(worker);
  counters_.results_redone += redone;
  Log(fmt::format("worker {} dropped for this run: {}; {} result(s) re-done",
                  worker, why, redone));
}

void FarmMasterCore::OnChunkRequest(const opt_chunk_request_t& msg,
                                    double now) {
  ++counters_.messages_received;
  if (msg.run_id != run_id_ || msg.scenario_hash != hash_) return;
  for (int index : msg.missing) {
    if (index < 0 || index >= static_cast<int>(chunks_.size())) {
      ++counters_.messages_malformed;
      continue;
    }
    if (now - chunk_sent_[index] < 0.1) continue;
    chunk_sent_[index] = now;
    opt_chunk_t chunk{};
    chunk.run_id = run_id_;
    chunk.scenario_hash = hash_;
    chunk.index = index;
    chunk.count = static_cast<int32_t>(chunks_.size());
    chunk.data.assign(chunks_[index].begin(), chunks_[index].end());
    chunk.size = static_cast<int32_t>(chunk.data.size());
    outbox_.chunks.push_back(std::move(chunk));
    ++counters_.chunks_sent;
  }
}

void FarmMasterCore::Announce(double now) {
  opt_run_t msg{};
  msg.run_id = run_id_;
  msg.started = started_;
  msg.heartbeat_period = heartbeat_period();
  msg.scenario_hash = hash_;
  msg.payload_size = static_cast<std::int64_t>(payload_.size());
  msg.chunk_count = static_cast<int32_t>(chunks_.size());
  msg.chunk_size = static_cast<int32_t>(chunks_.front().size());
  msg.copies = copies();
  outbox_.runs.push_back(std::move(msg));
  last_announce_ = now;
}

void FarmMasterCore::Requeue(std::int64_t job_id, const char* why) {
  Job* job = FindJob(job_id);
  if (!job || job->done || job->pending) return;
  auto w = workers_.find(job->worker);
  if (w != workers_.end()) w->second.assigned.erase(job_id);
  job->pending = true;
  ++pending_count_;
  dispatch_due_ = true;
  job->unlisted = 0;
  job->done_seen = -1;
  pending_.push_front(job_id);  // stragglers first
  Log(fmt::format("job {} re-queued: {}", job_id, why));
}

void FarmMasterCore::Maintain(double now) {
  last_maintain_ = now;
  const double silence = worker_timeout();
  for (auto it = workers_.begin(); it != workers_.end();) {
    Worker& w = it->second;
    if (now - w.last_seen > silence) {
      const size_t lost = w.assigned.size();
      std::vector<std::int64_t> ids(w.assigned.begin(), w.assigned.end());
      for (std::int64_t id : ids) Requeue(id, "its worker is gone");
      if (w.room_load >= 0) room_.erase({w.room_load, w.id});
      if (w.ready) --ready_count_;
      Log(fmt::format("worker {} is gone{}", it->first,
                      lost ? fmt::format("; {} job(s) re-queued", lost) : ""));
      it = workers_.erase(it);
      continue;
    }
    if (w.deaf_until > 0 && now >= w.deaf_until && w.room_load < 0) {
      Reindex(w, now);  // probation over: one more try
    }
    ++it;
  }
  const double timeout = JobTimeout();
  for (auto& [batch_id, batch] : batches_) {
    for (size_t i = 0; i < batch.jobs.size(); ++i) {
      Job& job = batch.jobs[i];
      if (job.done || job.pending) continue;
      const std::int64_t id =
          (batch_id << kJobIdShift) | static_cast<int64_t>(i);
      MaintainJob(id, job, timeout, now);
    }
  }
}

void FarmMasterCore::MaintainJob(std::int64_t id, Job& job, double timeout,
                                 double now) {
  if (now - job.sent > timeout) {
    Requeue(id, "no answer by its deadline");
    return;
  }
  if (job.poke_at <= 0) {
    // Sent before any episode time was known (a run's first jobs).
    const double wait = PokeWait(job);
    if (wait > 0) job.poke_at = job.sent + wait;
  }
  if (job.done_seen >= 0 && now - job.done_seen > settings_.result_wait) {
    // Its worker finished it but the result was lost: ask the same worker
    // again; it answers from its recent results without re-running.
    if (workers_.count(job.worker) == 0) return;
    SendAgain(id, job);
    job.done_seen = now;
    ++counters_.results_rerequested;
    return;
  }
  if (job.poke_at > 0 && now >= job.poke_at &&
      workers_.count(job.worker) != 0) {
    // Lost on the way there or back, or just slow: ask again (above).
    Poke(id, job, now);
  }
}

// A worker runs its jobs in the order they came, `slots` at a time: an
// earlier job still unanswered once `slots` later ones are was lost on its
// way there, or its result on the way back. It is asked again now, not at
// its poke deadline, so a lost datagram costs about one episode instead of
// three. The jobs queued behind the answered one move up a place, their
// deadlines counted from now. O(jobs the worker holds) per result.
void FarmMasterCore::Overtaken(Worker& w, const Job& answered, double now) {
  for (std::int64_t id : w.assigned) {
    Job* j = FindJob(id);
    if (!j || j->done || j->worker != w.id) continue;
    if (j->order < answered.order) {
      if (++j->overtaken == w.slots) Poke(id, *j, now);
    } else if (j->place > 1) {
      --j->place;
      const double wait = PokeWait(*j);
      if (wait > 0 && (j->poke_at <= 0 || now + wait < j->poke_at)) {
        j->poke_at = now + wait;
      }
    }
  }
}

// Asks the same worker again; the next time after twice as long.
void FarmMasterCore::Poke(std::int64_t job_id, Job& job, double now) {
  SendAgain(job_id, job);
  job.poke_at = now + 2 * (now - job.sent);
  ++counters_.jobs_poked;
}

void FarmMasterCore::SendAgain(std::int64_t job_id, Job& job) {
  QueueJob(job_id, job.worker);
}

void FarmMasterCore::QueueJob(std::int64_t job_id, const std::string& worker) {
  opt_job_t msg{};
  msg.run_id = run_id_;
  msg.scenario_hash = hash_;
  msg.worker_id = worker;
  msg.job_id = job_id;
  msg.generation = static_cast<int32_t>(job_id >> kJobIdShift);
  msg.index = static_cast<int32_t>(job_id & kIndexMask);
  msg.genome =
      OpenAt(job_id >> kJobIdShift).genomes[static_cast<size_t>(msg.index)];
  msg.gene_count = static_cast<int32_t>(msg.genome.size());
  outbox_.jobs.push_back(std::move(msg));
}

double FarmMasterCore::PokeWait(const Job& job) const {
  if (typical_episode_ <= 0 || settings_.poke_factor <= 0) return -1;
  return settings_.poke_margin +
         settings_.poke_factor * typical_episode_ * job.place;
}

double FarmMasterCore::MaintainPeriod() const {
  if (typical_episode_ <= 0) return kMaintainPeriod;
  return std::clamp(typical_episode_ / 2, kMinMaintainPeriod, kMaintainPeriod);
}

void FarmMasterCore::Send(std::int64_t job_id, Worker& w, double now) {
  Job& job = *FindJob(job_id);
  QueueJob(job_id, w.id);
  if (job.sends > 0) ++counters_.jobs_resent;
  ++counters_.jobs_sent;
  ++job.sends;
  if (job.pending) --pending_count_;
  job.pending = false;
  job.worker = w.id;
  job.sent = now;
  job.unlisted = 0;
  job.done_seen = -1;
  w.assigned.insert(job_id);
  job.place = static_cast<int>(w.assigned.size());
  job.order = ++send_order_;
  job.overtaken = 0;
  const double wait = PokeWait(job);
  job.poke_at = wait > 0 ? now + wait : 0;
  Reindex(w, now);
}

void FarmMasterCore::Dispatch(double now) {
  const double burst = std::max(1, settings_.dispatch_burst);
  if (settings_.dispatch_rate > 0) {
    tokens_ =
        std::min(burst, tokens_ + (now - tokens_at_) * settings_.dispatch_rate);
  } else {
    tokens_ = burst;  // no pace: only the burst limit
  }
  tokens_at_ = now;
  dispatch_due_ = false;
  std::vector<std::int64_t> waiting;
  while (!pending_.empty() && !room_.empty() && tokens_ >= 1) {
    const std::int64_t id = pending_.front();
    Job* job = FindJob(id);
    if (!job || job->done || !job->pending) {
      pending_.pop_front();  // stale
      continue;
    }
    // Least loaded first (ties by id); a re-sent job goes to another
    // worker than its last one when there is one with room; a job under
    // verification only to a worker that has not run it.
    auto slot = room_.begin();
    if (!job->opinions.empty()) {
      while (slot != room_.end() && Answered(*job, slot->second)) ++slot;
      if (slot == room_.end()) {
        waiting.push_back(id);  // until another worker has room
        pending_.pop_front();
        continue;
      }
    } else if (slot->second == job->worker && room_.size() > 1) {
      ++slot;
    }
    Worker& w = workers_.at(slot->second);
    if (slot->first >= w.slots &&
        pending_count_ <= static_cast<size_t>(std::max(ready_count_, 1))) {
      // Every worker is busy and no more than a round is left: each job
      // waits here for the first worker to finish instead (the tail).
      break;
    }
    pending_.pop_front();
    Send(id, w, now);
    tokens_ -= 1;
  }
  pending_.insert(pending_.begin(), waiting.begin(), waiting.end());
}

FarmOutbox FarmMasterCore::Tick(double now) {
  if (now - last_announce_ >= settings_.announce_period) Announce(now);
  if (now - last_maintain_ >= MaintainPeriod()) Maintain(now);
  Dispatch(now);
  FarmOutbox out;
  std::swap(out, outbox_);
  out.copies = copies();
  return out;
}

double FarmMasterCore::next_deadline() const {
  if (dispatch_due_) return 0;  // a new batch or re-queued jobs
  double t = std::min(last_announce_ + settings_.announce_period,
                      last_maintain_ + MaintainPeriod());
  if (tokens_ < 1 && settings_.dispatch_rate > 0 && !room_.empty() &&
      !pending_.empty()) {
    // Held back by the pace: go on when the next job may go out.
    t = std::min(t, tokens_at_ + (1 - tokens_) / settings_.dispatch_rate);
  }
  return t;
}

}  // namespace mrsim
