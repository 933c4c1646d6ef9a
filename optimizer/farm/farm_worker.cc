#include "optimizer/farm/farm_worker.h"

#include <fmt/format.h>
#include <unistd.h>

#include "common/wall_time.h"
#include "lcmtypes/runtime/decode.h"
#include "mrsim/opt_chunk_request_t.hpp"
#include "mrsim/opt_chunk_t.hpp"
#include "mrsim/opt_heartbeat_t.hpp"
#include "mrsim/opt_job_t.hpp"
#include "mrsim/opt_run_t.hpp"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/hash.h"
#include "optimizer/problem_codec.h"

namespace mrsim {
FarmWorker::FarmWorker(lcm::LCM& lcm, WorkerSettings settings)
    : lcm_(lcm), settings_(std::move(settings)) {
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  host_ = host;
  if (settings_.id.empty()) {
    settings_.id = fmt::format("{}-{}", host_, static_cast<int>(getpid()));
  }
  if (settings_.threads < 1) settings_.threads = 1;
  const FarmChannels ch(settings_.prefix);
  subscriptions_.push_back(lcm_.subscribe(ch.run, &FarmWorker::OnRun, this));
  subscriptions_.push_back(
      lcm_.subscribe(ch.chunk, &FarmWorker::OnChunk, this));
  subscriptions_.push_back(lcm_.subscribe(ch.job, &FarmWorker::OnJob, this));
  for (int t = 0; t < settings_.threads; ++t) {
    threads_.emplace_back([this] { Work(); });
  }
}

FarmWorker::~FarmWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

WorkerCounters FarmWorker::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

void FarmWorker::OnRun(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    opt_run_t msg;
    if (!DecodeMessage(rbuf, &msg) || msg.chunk_count < 1 ||
        msg.payload_size < 0 || msg.run_id.empty()) {
      CountMalformed();
      return;
    }
    const auto now = Clock::now();
    if (msg.run_id == run_id_ && msg.scenario_hash == hash_) {
      last_announce_ = now;
      return;
    }
    // Another run: follow it only when ours has gone quiet.
    if (!run_id_.empty() &&
        Seconds(now - last_announce_) < settings_.run_silence) {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counters_.messages_ignored;
      return;
    }
    if (msg.scenario_hash == bad_hash_) return;
    run_id_ = msg.run_id;
    hash_ = msg.scenario_hash;
    last_announce_ = now;
    problem_.reset();
    assembler_ = ChunkAssembler(msg.chunk_count, msg.payload_size);
    fetching_ = true;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const Task& t : queue_) held_.erase(t.job_id);
      queue_.clear();  // jobs of the old run are of no use now
    }
    log_.push_back(
        fmt::format("following run {} (payload {}, {} bytes in {} "
                    "chunks)",
                    run_id_, hash_, msg.payload_size, msg.chunk_count));
    RequestMissing();
  } catch (...) {
    CountMalformed();
  }
}

void FarmWorker::CountMalformed() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.messages_malformed;
}

void FarmWorker::OnChunk(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    opt_chunk_t msg;
    if (!DecodeMessage(rbuf, &msg)) {
      CountMalformed();
      return;
    }
    if (!fetching_ || msg.run_id != run_id_ || msg.scenario_hash != hash_ ||
        msg.count != assembler_.count()) {
      return;  // another run's, or one we already have: not an error
    }
    if (!assembler_.Add(msg.index,
                        std::string(msg.data.begin(), msg.data.end()))) {
      CountMalformed();
      return;
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
      problem_ = std::make_shared<const Problem>(
          DecodeProblem(payload, "payload " + hash_));
      log_.push_back(fmt::format("run {} ready", run_id_));
    } catch (const std::exception& e) {
      log_.push_back(std::string("cannot use the payload: ") + e.what());
      bad_hash_ = hash_;
      run_id_.clear();
      hash_.clear();
    }
  } catch (...) {
    CountMalformed();
  }
}

void FarmWorker::OnJob(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    opt_job_t msg;
    if (!DecodeMessage(rbuf, &msg)) {
      CountMalformed();
      return;
    }
    if (msg.worker_id != settings_.id) return;  // someone else's job
    std::lock_guard<std::mutex> lock(mutex_);
    if (!problem_ || msg.run_id != run_id_ || msg.scenario_hash != hash_) {
      ++counters_.messages_ignored;
      return;
    }
    if (static_cast<int>(msg.genome.size()) != problem_->genome.size()) {
      ++counters_.messages_malformed;
      return;
    }
    if (held_.count(msg.job_id)) return;  // a re-send of one we hold
    Task task;
    task.problem = problem_;
    task.run_id = msg.run_id;
    task.hash = msg.scenario_hash;
    task.job_id = msg.job_id;
    task.generation = msg.generation;
    task.index = msg.index;
    task.genome = msg.genome;
    held_.insert(msg.job_id);
    queue_.push_back(std::move(task));
    wake_.notify_one();
  } catch (...) {
    CountMalformed();
  }
}

void FarmWorker::Work() {
  for (;;) {
    Task task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return quit_ || !queue_.empty(); });
      if (quit_) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    opt_result_t r;
    r.run_id = task.run_id;
    r.scenario_hash = task.hash;
    r.worker_id = settings_.id;
    r.job_id = task.job_id;
    r.generation = task.generation;
    r.index = task.index;
    r.fitness = r.distance = r.speed = r.energy = r.drift = r.fell = 0;
    r.failed = false;
    const auto t0 = Clock::now();
    try {
      task.problem->genome.Check(task.genome);
      const EvalResult e = RunEpisode(*task.problem, task.genome);
      r.fitness = e.fitness;
      r.distance = e.distance;
      r.speed = e.speed;
      r.energy = e.energy;
      r.drift = e.drift;
      r.fell = e.fell;
      r.failed = e.failed;
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    r.eval_seconds = Seconds(Clock::now() - t0);
    std::lock_guard<std::mutex> lock(mutex_);
    held_.erase(task.job_id);
    ++counters_.jobs_done;
    finished_.push_back(std::move(r));
  }
}

void FarmWorker::RequestMissing() {
  if (!fetching_) return;
  opt_chunk_request_t req;
  req.utime = WallMicros();
  req.run_id = run_id_;
  req.scenario_hash = hash_;
  req.worker_id = settings_.id;
  req.missing = assembler_.Missing(256);
  req.count = static_cast<int32_t>(req.missing.size());
  lcm_.publish(FarmChannels(settings_.prefix).chunk_request, &req);
  last_request_ = Clock::now();
}

std::vector<std::string> FarmWorker::Poll() {
  const FarmChannels ch(settings_.prefix);
  std::vector<opt_result_t> done;
  opt_heartbeat_t hb;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done.swap(finished_);
    hb.jobs.assign(held_.begin(), held_.end());
    hb.jobs_done = counters_.jobs_done;
    hb.messages_ignored = counters_.messages_ignored;
    hb.messages_malformed = counters_.messages_malformed;
  }
  for (opt_result_t& r : done) {
    r.utime = WallMicros();
    lcm_.publish(ch.result, &r);
  }
  const auto now = Clock::now();
  if (fetching_ && Seconds(now - last_request_) >= settings_.request_period) {
    RequestMissing();
  }
  if (!done.empty() ||
      Seconds(now - last_heartbeat_) >= settings_.heartbeat_period) {
    hb.utime = WallMicros();
    hb.worker_id = settings_.id;
    hb.host = host_;
    hb.pid = static_cast<int32_t>(getpid());
    if (problem_) {
      hb.run_id = run_id_;
      hb.scenario_hash = hash_;
    }
    hb.slots = settings_.threads;
    hb.job_count = static_cast<int32_t>(hb.jobs.size());
    lcm_.publish(ch.heartbeat, &hb);
    last_heartbeat_ = now;
  }
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

}  // namespace mrsim
