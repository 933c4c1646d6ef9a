// The farm worker's logic without LCM, threads or a clock: follows the
// newest master's run, fetches its payload in chunks, queues the jobs
// addressed to it and hands them out to run (at most `threads` at once),
// beats, and answers re-asked jobs from its recent results. FarmWorker
// wires it to LCM and a thread pool; tests drive it with a fake clock.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "lcmtypes/runtime/message_key.h"
#include "optimizer/episode/episode.h"
#include "optimizer/farm/build_fingerprint.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_outbox.h"
#include "optimizer/farm/payload_chunks.h"

namespace mrsim {

struct WorkerSettings {
  std::string prefix = kDefaultFarmPrefix;
  AuthConfig auth;  // the key messages are signed with (none: unsigned)
  std::string build = BuildFingerprint();  // announced in heartbeats
  // For tests of --verify only: adds this to every fitness it reports (a
  // worker that lies). 0 in every real use.
  double lie = 0.0;
  std::string id;  // unique on the network; default host-pid
  int threads = 1;
  double heartbeat_period = 0.2;  // s, until a master asks for another
  double request_period = 0.3;    // s between asks for missing chunks
  // s without announcement before following an older master's run (a
  // newer master, e.g. a restarted one, is followed at once).
  double run_silence = 3.0;
  // s without hearing our master before re-joining (re-creating the LCM
  // connection); doubles on each further silence, up to 30 s.
  double rejoin_silence = 2.0;
  // Protocol-only worker: an "episode" takes this many seconds and scores
  // a function of the genome, with no physics (0: real episodes).
  double fake_episode = 0.0;
};

struct WorkerCounters {
  long long jobs_done = 0;
  long long messages_ignored = 0;  // other run, payload or worker
  long long messages_malformed = 0;
  long long results_resent = 0;  // re-asked jobs answered from memory
  long long rejoins = 0;
  long long heartbeats_sent = 0;
};

// One job to run: the decoded problem it belongs to and the genome.
struct WorkerTask {
  std::shared_ptr<const Problem> problem;
  std::string run_id, hash;
  std::int64_t job_id = 0;
  std::int32_t generation = 0, index = 0;
  Genome genome;
};

class FarmWorkerCore {
 public:
  // The largest announcement followed: a payload of at most 256 MB in at
  // most 65536 chunks of at most 65536 bytes (opt_chunk_t's limit), as many
  // as the payload needs. A forged announcement of 2^31 chunks once made
  // the worker allocate 64 GB.
  static constexpr long long kMaxPayloadBytes = 256LL << 20;
  static constexpr int kMaxChunks = 65536;
  static constexpr int kMaxChunkBytes = 65536;

  // Turns a payload whose hash matched into a problem (throws naming what
  // is wrong). Default: DecodeProblem.
  using Decoder = std::function<std::shared_ptr<const Problem>(
      const std::string& payload, const std::string& hash)>;

  FarmWorkerCore(WorkerSettings settings, std::string host, int pid,
                 Decoder decode = {});

  void OnRun(const opt_run_t& msg, double now);
  void OnChunk(const opt_chunk_t& msg, double now);
  void OnJob(const opt_job_t& msg, double now);
  // An episode handed out by TakeTasks ended (result filled in but utime).
  void OnEpisodeDone(opt_result_t result, double now);
  void CountMalformed() { ++counters_.messages_malformed; }
  // A job handed out by TakeTasks that will not be run after all.
  void Forget(std::int64_t job_id) { running_.erase(job_id); }

  // Jobs to start now: at most `threads` running plus `ahead` handed out
  // to wait in the runner's own queue, so a thread that ends an episode
  // starts the next without a round trip through this core.
  std::vector<WorkerTask> TakeTasks(int ahead = 0);
  // Heartbeats, chunk requests, results; everything to publish.
  FarmOutbox Tick(double now);
  double next_deadline() const;
  double last_tick() const { return last_tick_; }
  std::vector<std::string> TakeLog();

  const std::string& id() const { return settings_.id; }
  const std::string& run_id() const { return run_id_; }
  bool ready() const { return problem_ != nullptr; }
  const std::shared_ptr<const Problem>& problem() const { return problem_; }
  int held() const { return static_cast<int>(queue_.size() + running_.size()); }
  double heartbeat_period() const { return heartbeat_period_; }
  const WorkerCounters& counters() const { return counters_; }

 private:
  void Follow(const opt_run_t& msg, double now);
  void TakeAnnouncement(const opt_run_t& msg, double now);
  void RequestMissing(double now);

  WorkerSettings settings_;
  std::string host_;
  int pid_;
  Decoder decode_;

  std::string run_id_, hash_;
  std::int64_t run_started_ = 0;
  double last_announce_ = 0;
  double heartbeat_period_;
  int copies_ = 1;  // of each result, as the master asks
  ChunkAssembler assembler_;
  bool fetching_ = false;
  double last_chunk_ = -1e9;  // when a new chunk last arrived
  std::shared_ptr<const Problem> problem_;
  std::string problem_hash_;  // the payload problem_ was decoded from
  std::string bad_hash_;      // a payload that did not decode: not retried
  double last_heartbeat_ = -1e9, last_request_ = -1e9;
  double phase_;  // spreads the heartbeats of many workers
  double rejoin_backoff_ = 0, last_rejoin_ = -1e9;
  bool heard_master_ = false;
  long long heard_ = 0;  // messages of any run or worker, for the log
  long long heard_at_announce_ = 0;
  double last_tick_ = -1e9;

  std::deque<WorkerTask> queue_;
  std::set<std::int64_t> queued_ids_;
  std::map<std::int64_t, Genome> running_;
  // Recent results (for re-asked jobs and the heartbeat's done list), with
  // their genomes: a job id is answered from memory only for the same
  // genome of the same run.
  struct Recent {
    double when;
    opt_result_t result;
    Genome genome;
  };
  std::deque<Recent> recent_;
  std::vector<std::string> log_;
  WorkerCounters counters_;
  FarmOutbox outbox_;
};

}  // namespace mrsim
