// The farm master's logic without LCM or a clock: decoded worker messages
// and the current time in, messages to publish out (FarmEvaluator wires it
// to LCM; tests drive it with a fake clock and simulated workers).
//
// Every message costs O(log workers): workers with room sit in a set
// ordered by load, so each ready worker gets a job before any gets a
// second; silence and deadlines are checked on a timer, not per message.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lcmtypes/runtime/message_key.h"
#include "optimizer/search/eval_result.h"
#include "optimizer/farm/build_fingerprint.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_outbox.h"
#include "optimizer/search/genome.h"

namespace mrsim {

struct FarmSettings {
  std::string prefix = kDefaultFarmPrefix;
  AuthConfig auth;  // the key messages are signed with (none: unsigned)
  // This master's build; workers announcing another are refused unless
  // allow_mixed_builds (their results could differ from a local run's).
  std::string build = BuildFingerprint();
  bool allow_mixed_builds = false;
  // Fraction of jobs (0..1, spread evenly) run again on a different worker.
  // Where two results of a job differ, a third worker decides; a worker
  // outvoted is dropped for the run and every result of it in the open
  // batches is re-done (BOINC's redundancy). Same build, same genome: the
  // very same numbers, so any difference is a fault or a lie.
  double verify = 0.0;
  // A job is re-sent when not answered this long after it was sent; 0:
  // automatic (10 s, then 3 x the slowest episode seen x the jobs a worker
  // holds, plus 2 s).
  double job_timeout = 0.0;
  // s without a heartbeat or result before a worker counts as gone (at least
  // five heartbeat periods plus a second).
  double worker_timeout = 2.0;
  // Jobs queued at a busy worker beyond its slots, so its next episode
  // starts without waiting for a round trip. Only while more than one job
  // per ready worker is waiting: near a generation's end a job queued
  // behind a slow episode would wait while another worker sits idle.
  int extra_jobs_per_worker = 1;
  double announce_period = 0.5;  // s
  // Payload bytes per chunk; 0: what fits one 1500-byte Ethernet frame
  // with the chunk's header (one IP packet: a lost fragment loses only it).
  int chunk_size = 0;
  // Heartbeats asked of the workers: every max(min_heartbeat_period,
  // workers / heartbeat_budget) s, so the master hears at most about
  // heartbeat_budget heartbeats a second however large the farm grows.
  double min_heartbeat_period = 0.2;
  double heartbeat_budget = 250.0;
  double result_wait = 1.0;  // s after a heartbeat lists a job done before
                             // its result is asked for again
  // A job still unanswered poke_factor x the typical episode (times its
  // place in its worker's queue) plus poke_margin s after it went out is
  // sent again to the same worker, then after twice as long, and so on: a
  // worker that never got it runs it, one that finished it answers from
  // memory, one that is still at it ignores it. One lost datagram then
  // costs a few episodes' time, not the job deadline.
  double poke_factor = 2.0;
  double poke_margin = 0.03;  // s
  // Jobs go out at most dispatch_burst at once and dispatch_rate a second
  // on average: a generation of thousands in one burst overflows a
  // receiver's socket buffer (a stock 416 KB holds ~400 small datagrams)
  // whenever its receive thread is not scheduled for a few ms.
  int dispatch_burst = 256;
  double dispatch_rate = 25600;  // jobs/s (256 every 10 ms)
  // Each job (and, told by the announcement, each result) is sent this
  // many times; 0: automatic, 2 while the farm has at most duplicate_up_to
  // workers, 1 beyond (where the datagrams would cost more than a rare
  // lost one). Receivers drop the second copy.
  int copies = 0;
  int duplicate_up_to = 64;
  std::function<bool()> stop;  // polled; true abandons the batch
  std::function<void(const std::string&)> log;  // events (worker joined...)
};

struct FarmCounters {
  long long jobs_sent = 0;
  long long jobs_resent = 0;
  long long results_accepted = 0;
  long long results_ignored = 0;  // late, duplicate, other run or payload
  long long results_rerequested = 0;
  long long jobs_poked = 0;  // sent again to the same worker (poke_factor)
  long long messages_malformed = 0;
  long long chunks_sent = 0;
  long long messages_received = 0;
  long long heartbeats_received = 0;
  long long heartbeats_refused = 0;  // workers of another build
  long long results_verified = 0;    // jobs whose results two workers agreed
  long long workers_dropped = 0;     // outvoted by verification
  long long results_redone = 0;      // accepted, then re-done (worker dropped)
  // Sum over finished batches of the busiest worker's episode seconds in
  // it: no dispatch can end a batch sooner (the generation barrier), so
  // episode_seconds / (workers x this) is the most a farm of equal
  // workers can reach with these episodes, and this / wall time what
  // the farm's own latencies leave of it.
  double busiest_worker_seconds = 0.0;
};

// The largest chunk whose opt_chunk_t, with LCM's header and the channel
// name, fits one 1472-byte UDP datagram (1500-byte MTU).
int OnePacketChunkSize(const std::string& prefix, const std::string& run_id,
                       const std::string& hash);

class FarmMasterCore {
 public:
  // `payload` is EncodeProblem's output; `run_id` tells this master's
  // messages apart from any other's; `started_utime` orders masters (the
  // newest is followed at once).
  FarmMasterCore(std::string payload, std::string run_id,
                 std::int64_t started_utime, FarmSettings settings);

  // Starts a batch alone: the open ones are closed first (their late
  // answers are ignored from now).
  void StartBatch(const std::vector<Genome>& batch, double now);
  // Opens a batch beside the open ones and returns its id. Its jobs go out
  // after theirs, so workers that finish the older batch's last jobs early
  // go on with this one instead of waiting (several generations in flight).
  std::int64_t OpenBatch(const std::vector<Genome>& batch);
  // Forgets a batch (done or not): its late answers are ignored.
  void CloseBatch(std::int64_t id, double now);
  // The newest batch's state, or batch `id`'s (an unknown id throws
  // std::out_of_range).
  bool batch_done() const { return batch_done(batch_); }
  bool batch_done(std::int64_t id) const { return OpenAt(id).remaining == 0; }
  const std::vector<EvalResult>& results() const { return results(batch_); }
  const std::vector<EvalResult>& results(std::int64_t id) const {
    return OpenAt(id).results;
  }
  // Why the batch cannot finish ("" while it can): a job that
  // kMaxJobErrors answers said could not be run. The same genome fails
  // the same way on every worker, so asking again would loop forever.
  const std::string& failure() const { return failure_; }
  static constexpr int kMaxJobErrors = 3;

  void OnHeartbeat(const opt_heartbeat_t& msg, double now);
  void OnResult(const opt_result_t& msg, double now);
  void OnChunkRequest(const opt_chunk_request_t& msg, double now);
  void CountMalformed() { ++counters_.messages_malformed; }

  // Announces, checks silence and deadlines, dispatches; returns everything
  // to publish since the last call.
  FarmOutbox Tick(double now);
  // When Tick next has timed work (announce, maintenance).
  double next_deadline() const;

  int workers_alive() const { return static_cast<int>(workers_.size()); }
  int workers_ready() const { return ready_count_; }
  double heartbeat_period() const;
  int copies() const;
  double worker_timeout() const;
  double JobTimeout() const;
  const std::string& scenario_hash() const { return hash_; }
  const std::string& run_id() const { return run_id_; }
  int chunk_count() const { return static_cast<int>(chunks_.size()); }
  const FarmCounters& counters() const { return counters_; }
  // Sum of the workers' reported episode wall times (s), for overhead.
  double episode_seconds() const { return episode_seconds_; }

 private:
  struct Worker {
    std::string id;
    bool ready = false;  // holds our payload
    int slots = 1;
    double last_seen = 0;
    std::set<std::int64_t> assigned;  // sent, not answered
    int room_load = -1;               // its key in room_ (-1: not there)
    int misses = 0;                   // jobs in a row it never listed
    double deaf_until = 0;
    double deaf_backoff = 0;
  };
  struct Job {
    bool done = false;
    bool pending = true;  // waiting in pending_ to be (re)sent
    std::string worker;   // latest assignee
    int sends = 0;
    double sent = 0;
    int unlisted = 0;        // heartbeats of its worker not listing it
    double done_seen = -1;   // a heartbeat listed it done; result not here
    int place = 1;           // jobs its worker held with it when sent
    double poke_at = 0;      // when to send it again to the same worker
    std::int64_t order = 0;  // when it went out, among every send
    int overtaken = 0;       // results of its worker's later jobs since
    int errors = 0;          // workers that answered they could not run it
    bool verify = false;     // needs results from two workers that agree
    // Results so far of a job under verification, by worker.
    std::vector<std::pair<std::string, EvalResult>> opinions;
  };

  // One open batch: its jobs and what came back.
  struct Batch {
    std::vector<Genome> genomes;
    std::vector<Job> jobs;
    std::vector<EvalResult> results;
    size_t remaining = 0;
    // Each worker's episode seconds in it, and the largest of them.
    std::unordered_map<std::string, double> worker_seconds;
    double busiest = 0.0;
  };

  const Batch& OpenAt(std::int64_t id) const;
  void Announce(double now);
  void Maintain(double now);
  void MaintainJob(std::int64_t id, Job& job, double timeout, double now);
  void Dispatch(double now);
  void Send(std::int64_t job_id, Worker& w, double now);
  void SendAgain(std::int64_t job_id, Job& job);
  void Poke(std::int64_t job_id, Job& job, double now);
  void Overtaken(Worker& w, const Job& answered, double now);
  // The job message for `worker`, into the outbox (no bookkeeping).
  void QueueJob(std::int64_t job_id, const std::string& worker);
  double PokeWait(const Job& job) const;
  double MaintainPeriod() const;
  void Requeue(std::int64_t job_id, const char* why);
  void Reindex(Worker& w, double now);
  Job* FindJob(std::int64_t job_id);
  // Takes `r` as job `job_id`'s result, answered by `worker`.
  void Accept(std::int64_t job_id, Job& job, const EvalResult& r,
              const std::string& worker, double eval_seconds, double now);
  // A result of a job under verification.
  void Verify(std::int64_t job_id, Job& job, const EvalResult& r,
              const std::string& worker, double eval_seconds, double now);
  // Drops a worker for the run and re-does every result it gave.
  void Drop(const std::string& worker, const std::string& why);
  // Whether `worker` already gave job `job` a result (verification).
  static bool Answered(const Job& job, const std::string& worker);
  void Log(const std::string& text) const;

  std::string payload_;
  std::string run_id_;
  std::string hash_;
  std::string failure_;
  bool warned_other_run_ = false;  // another master on our prefix, said
  std::set<std::string> refused_;  // workers of another build, said once
  std::set<std::string> dropped_;  // outvoted: ignored for the rest of the run
  // Jobs of the open batches each worker's result was taken for.
  std::unordered_map<std::string, std::vector<std::int64_t>> results_by_;
  long long jobs_opened_ = 0;  // every job so far, for the verify spread
  std::int64_t started_;
  FarmSettings settings_;
  std::vector<std::string> chunks_;
  // When each chunk last went out: workers asking together get one copy
  // (it reaches all of them).
  std::vector<double> chunk_sent_;

  std::unordered_map<std::string, Worker> workers_;
  std::set<std::pair<int, std::string>> room_;  // (load, id), ready, room
  std::map<std::int64_t, Batch> batches_;       // open, oldest first
  std::deque<std::int64_t> pending_;            // may hold stale ids
  size_t pending_count_ = 0;                    // live ids in pending_
  int ready_count_ = 0;                         // workers holding our payload
  bool dispatch_due_ = false;  // jobs became pending since the last Tick
  std::int64_t batch_ = 0;     // the newest batch's id
  double last_announce_ = -1e9;
  double last_maintain_ = -1e9;
  std::int64_t send_order_ = 0;  // Job::order of the latest send
  double tokens_ = 0;            // jobs that may go out now (dispatch pace)
  double tokens_at_ = -1e9;
  double slowest_episode_ = 0.0;
  double typical_episode_ = 0.0;  // moving average of the reported times
  double episode_seconds_ = 0.0;
  FarmCounters counters_;
  FarmOutbox outbox_;
};

}  // namespace mrsim
