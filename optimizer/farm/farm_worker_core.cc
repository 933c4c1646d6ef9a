#include "optimizer/farm/farm_worker_core.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/hash.h"
#include "optimizer/episode/problem_codec.h"

namespace mrsim {
namespace {

constexpr size_t kRecentResults = 64;

}  // namespace

FarmWorkerCore::FarmWorkerCore(WorkerSettings settings, std::string host,
                               int pid, Decoder decode)
    : settings_(std::move(settings)),
      host_(std::move(host)),
      pid_(pid),
      decode_(std::move(decode)),
      heartbeat_period_(settings_.heartbeat_period) {
  if (settings_.threads < 1) settings_.threads = 1;
  if (settings_.id.empty()) settings_.id = fmt::format("{}-{}", host_, pid_);
  if (!decode_) {
    decode_ = [](const std::string& payload, const std::string& hash) {
      return std::make_shared<const Problem>(
          DecodeProblem(payload, "payload " + hash));
    };
  }
  // A fixed fraction of the period per worker id, so a farm started at once
  // does not beat in step.
  phase_ = static_cast<double>(Fnv1a64(settings_.id) % 1000) / 1000.0;
}

std::vector<std::string> FarmWorkerCore::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

namespace {

// An announcement a master could have sent (see kMaxPayloadBytes).
bool PlausibleRun(const opt_run_t& msg) {
  if (msg.run_id.empty() || msg.payload_size < 0 ||
      msg.payload_size > FarmWorkerCore::kMaxPayloadBytes ||
      msg.chunk_count < 1 || msg.chunk_count > FarmWorkerCore::kMaxChunks ||
      msg.chunk_size < 0 || msg.chunk_size > FarmWorkerCore::kMaxChunkBytes) {
    return false;
  }
  if (msg.payload_size == 0) return msg.chunk_count == 1;
  if (msg.chunk_size == 0) return false;
  const long long needed =
      (msg.payload_size + msg.chunk_size - 1) / msg.chunk_size;
  return msg.chunk_count == needed;
}

}  // namespace

void FarmWorkerCore::OnRun(const opt_run_t& msg, double now) {
  ++heard_;
  if (!PlausibleRun(msg)) {
    ++counters_.messages_malformed;
    return;
  }
  if (msg.run_id == run_id_ && msg.scenario_hash == hash_) {
    TakeAnnouncement(msg, now);
    return;
  }
  // Another run: a newer master (a restart) at once, an older one only
  // when ours has gone quiet.
  const bool newer = msg.started > run_started_;
  if (!run_id_.empty() && !newer &&
      now - last_announce_ < settings_.run_silence) {
    ++counters_.messages_ignored;
    return;
  }
  if (msg.scenario_hash == bad_hash_) return;
  Follow(msg, now);
}

// What every announcement of the followed run tells: the master is there,
// and how often to heartbeat and how many copies to send.
void FarmWorkerCore::TakeAnnouncement(const opt_run_t& msg, double now) {
  last_announce_ = now;
  heard_at_announce_ = heard_;
  heard_master_ = true;
  rejoin_backoff_ = 0;
  if (msg.heartbeat_period > 0 && msg.heartbeat_period < 3600) {
    heartbeat_period_ =
        std::max(settings_.heartbeat_period, msg.heartbeat_period);
  }
  copies_ = std::clamp(msg.copies, 1, 4);
}

void FarmWorkerCore::Follow(const opt_run_t& msg, double now) {
  run_id_ = msg.run_id;
  hash_ = msg.scenario_hash;
  run_started_ = msg.started;
  TakeAnnouncement(msg, now);
  for (const WorkerTask& t : queue_) queued_ids_.erase(t.job_id);
  queue_.clear();  // jobs of the old run are of no use now
  if (problem_ && problem_hash_ == hash_) {
    fetching_ = false;  // the same payload (a restarted master)
    log_.push_back(fmt::format("following run {} (payload {} already here)",
                               run_id_, hash_));
    return;
  }
  problem_.reset();
  problem_hash_.clear();
  assembler_ = ChunkAssembler(msg.chunk_count, msg.payload_size);
  fetching_ = true;
  log_.push_back(
      fmt::format("following run {} (payload {}, {} bytes in {} chunks)",
                  run_id_, hash_, msg.payload_size, msg.chunk_count));
  RequestMissing(now);
}

void FarmWorkerCore::OnChunk(const opt_chunk_t& msg, double now) {
  ++heard_;
  if (!fetching_ || msg.run_id != run_id_ || msg.scenario_hash != hash_ ||
      msg.count != assembler_.count()) {
    return;  // another run's, or one we already have: not an error
  }
  const int before = assembler_.received();
  if (!assembler_.Add(msg.index,
                      std::string(msg.data.begin(), msg.data.end()))) {
    ++counters_.messages_malformed;
    return;
  }
  if (assembler_.received() > before) {
    last_chunk_ = now;
  }
  if (!assembler_.complete()) return;
  fetching_ = false;
  const std::string payload = assembler_.Join();
  if (HashHex(Fnv1a64(payload)) != hash_) {
    log_.push_back("payload hash mismatch; fetching it again");
    assembler_ = ChunkAssembler(assembler_.count(),
                                static_cast<long long>(payload.size()));
    fetching_ = true;
    return;
  }
  try {
    problem_ = decode_(payload, hash_);
    problem_hash_ = hash_;
    log_.push_back(fmt::format("run {} ready", run_id_));
  } catch (const std::exception& e) {
    log_.push_back(std::string("cannot use the payload: ") + e.what());
    bad_hash_ = hash_;
    run_id_.clear();
    hash_.clear();
  }
}

void FarmWorkerCore::OnJob(const opt_job_t& msg, double now) {
  (void)now;
  ++heard_;
  if (msg.worker_id != settings_.id) return;  // someone else's job
  if (!problem_ || msg.run_id != run_id_ || msg.scenario_hash != hash_) {
    ++counters_.messages_ignored;
    return;
  }
  if (queued_ids_.count(msg.job_id) || running_.count(msg.job_id)) return;
  for (const Recent& r : recent_) {
    if (r.result.job_id == msg.job_id && r.result.run_id == msg.run_id &&
        r.genome == msg.genome) {
      // Asked again after we finished it: the answer was lost.
      outbox_.results.push_back(r.result);
      ++counters_.results_resent;
      return;
    }
  }
  WorkerTask task;
  task.problem = problem_;
  task.run_id = msg.run_id;
  task.hash = msg.scenario_hash;
  task.job_id = msg.job_id;
  task.generation = msg.generation;
  task.index = msg.index;
  task.genome = msg.genome;
  queued_ids_.insert(msg.job_id);
  queue_.push_back(std::move(task));
}

std::vector<WorkerTask> FarmWorkerCore::TakeTasks(int ahead) {
  std::vector<WorkerTask> out;
  while (!queue_.empty() && static_cast<int>(running_.size()) <
                                settings_.threads + std::max(0, ahead)) {
    WorkerTask t = std::move(queue_.front());
    queue_.pop_front();
    queued_ids_.erase(t.job_id);
    running_[t.job_id] = t.genome;
    out.push_back(std::move(t));
  }
  return out;
}

void FarmWorkerCore::OnEpisodeDone(opt_result_t result, double now) {
  Genome genome;
  auto it = running_.find(result.job_id);
  if (it != running_.end()) {
    genome = std::move(it->second);
    running_.erase(it);
  }
  ++counters_.jobs_done;
  if (result.error.empty()) result.fitness += settings_.lie;
  recent_.push_back(Recent{now, result, std::move(genome)});
  while (recent_.size() > kRecentResults) recent_.pop_front();
  outbox_.results.push_back(std::move(result));
}

void FarmWorkerCore::RequestMissing(double now) {
  if (!fetching_) return;
  opt_chunk_request_t req{};
  req.run_id = run_id_;
  req.scenario_hash = hash_;
  req.worker_id = settings_.id;
  req.missing = assembler_.Missing(256);
  req.count = static_cast<int32_t>(req.missing.size());
  outbox_.chunk_requests.push_back(std::move(req));
  last_request_ = now;
}

FarmOutbox FarmWorkerCore::Tick(double now) {
  last_tick_ = now;
  // Ask for missing chunks only when none arrived lately: while chunks flow
  // (someone else asked for them too) asking again adds nothing.
  if (fetching_ && now - last_request_ >= settings_.request_period &&
      now - last_chunk_ >= settings_.request_period) {
    RequestMissing(now);
  }
  if (now - last_heartbeat_ >= heartbeat_period_) {
    opt_heartbeat_t hb{};
    hb.worker_id = settings_.id;
    hb.host = host_;
    hb.pid = pid_;
    if (problem_) {
      hb.run_id = run_id_;
      hb.scenario_hash = hash_;
    }
    hb.slots = settings_.threads;
    hb.build = settings_.build;
    hb.jobs.assign(queued_ids_.begin(), queued_ids_.end());
    for (const auto& [id, genome] : running_) hb.jobs.push_back(id);
    hb.job_count = static_cast<int32_t>(hb.jobs.size());
    // Finished within the last few heartbeats: a heartbeat that overtakes
    // a result must not make the master think the job was lost.
    // (the last 32, for 10 s or three heartbeats, whichever is longer).
    const double window = std::max(10.0, 3 * heartbeat_period_ + 1.0);
    for (auto it = recent_.rbegin();
         it != recent_.rend() && hb.done.size() < 32; ++it) {
      if (now - it->when <= window) hb.done.push_back(it->result.job_id);
    }
    hb.done_count = static_cast<int32_t>(hb.done.size());
    hb.jobs_done = counters_.jobs_done;
    hb.messages_ignored = counters_.messages_ignored;
    hb.messages_malformed = counters_.messages_malformed;
    outbox_.heartbeats.push_back(std::move(hb));
    ++counters_.heartbeats_sent;
    // The first beat comes at once; the next ones on the worker's phase.
    last_heartbeat_ =
        last_heartbeat_ < -1e8 ? now - phase_ * heartbeat_period_ : now;
  }
  // Our master fell silent: maybe it is gone, maybe we lost the multicast
  // group (a link flap). Re-joining costs nothing, so do it, less and less
  // often while the silence lasts.
  if (heard_master_) {
    const double wait =
        rejoin_backoff_ > 0 ? rejoin_backoff_ : settings_.rejoin_silence;
    if (now - last_announce_ >= wait && now - last_rejoin_ >= wait) {
      outbox_.rejoin = true;
      last_rejoin_ = now;
      rejoin_backoff_ = std::min(
          30.0, std::max(settings_.rejoin_silence, rejoin_backoff_ * 2));
      ++counters_.rejoins;
      // How much else arrived meanwhile tells a lost group membership
      // (nothing) from announcements lost or not sent (other traffic).
      log_.push_back(fmt::format(
          "no announcement for {:.1f} s ({} other messages heard since the "
          "last); re-joining the LCM group",
          now - last_announce_, heard_ - heard_at_announce_));
    }
  }
  FarmOutbox out;
  std::swap(out, outbox_);
  out.copies = copies_;
  return out;
}

double FarmWorkerCore::next_deadline() const {
  double t = last_heartbeat_ + heartbeat_period_;
  if (fetching_) t = std::min(t, last_request_ + settings_.request_period);
  return t;
}

}  // namespace mrsim
