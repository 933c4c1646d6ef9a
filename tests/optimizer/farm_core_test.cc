// The farm's master and worker cores in one process on a fake clock
// (tests/optimizer/sim_farm.h): dispatch, deadlines, re-sends, late and
// duplicate answers, workers joining and leaving, lost chunks, a deaf
// worker and a master restart. No sockets, no sleeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_master_core.h"
#include "optimizer/farm/farm_worker_core.h"
#include "tests/optimizer/sim_farm.h"

namespace mrsim {
namespace {

using testing::SimFarm;
using testing::SimFitness;
using testing::SimNetwork;

std::string Payload(size_t size) {
  std::string p(size, '\0');
  for (size_t i = 0; i < size; ++i) p[i] = static_cast<char>(i * 131 % 251);
  return p;
}

std::vector<Genome> Batch(int n, int generation) {
  std::vector<Genome> batch;
  Random random(static_cast<std::uint64_t>(generation) + 7);
  for (int i = 0; i < n; ++i) {
    batch.push_back(
        {random.Uniform(0, 2), random.Uniform(0, 2), random.Uniform(0, 2)});
  }
  return batch;
}

// Runs `generations` batches; every result must be the genome's own.
void RunAndCheck(SimFarm& farm, int generations, int population,
                 double limit_per_generation = 600) {
  for (int g = 0; g < generations; ++g) {
    const std::vector<Genome> batch = Batch(population, g);
    std::vector<EvalResult> results;
    ASSERT_TRUE(farm.Evaluate(batch, limit_per_generation, &results))
        << "generation " << g << " did not finish by simulated " << farm.now()
        << " s";
    ASSERT_EQ(results.size(), batch.size());
    for (size_t i = 0; i < batch.size(); ++i) {
      EXPECT_EQ(results[i].fitness, SimFitness(batch[i])) << "gen " << g;
    }
  }
}

opt_heartbeat_t Beat(const FarmMasterCore& m, const std::string& id,
                     std::vector<std::int64_t> held = {},
                     std::vector<std::int64_t> done = {}) {
  opt_heartbeat_t hb{};
  hb.worker_id = id;
  hb.run_id = m.run_id();
  hb.scenario_hash = m.scenario_hash();
  hb.slots = 1;
  hb.build = BuildFingerprint();
  hb.jobs = std::move(held);
  hb.job_count = static_cast<int32_t>(hb.jobs.size());
  hb.done = std::move(done);
  hb.done_count = static_cast<int32_t>(hb.done.size());
  return hb;
}

TEST(FarmMasterCore, WorkerOfAnotherBuildIsRefusedUnlessMixedBuildsAllowed) {
  std::vector<std::string> log;
  FarmSettings settings;
  settings.log = [&](const std::string& line) { log.push_back(line); };
  FarmMasterCore m(Payload(100), "run", 1, settings);
  opt_heartbeat_t other = Beat(m, "odd");
  other.build = "mrsim 0.0.1; gcc 9; MuJoCo 2.3.0; x86_64";
  m.OnHeartbeat(other, 0.0);
  m.OnHeartbeat(other, 0.1);
  m.OnHeartbeat(Beat(m, "same"), 0.0);
  EXPECT_EQ(m.workers_alive(), 1);
  EXPECT_EQ(m.counters().heartbeats_refused, 2);
  // Said once, naming the worker and both builds.
  const auto said = std::count_if(log.begin(), log.end(), [](const auto& l) {
    return l.find("refused worker odd") != std::string::npos;
  });
  EXPECT_EQ(said, 1);
  m.StartBatch(Batch(4, 0), 0.0);
  for (const auto& job : m.Tick(0.0).jobs) EXPECT_EQ(job.worker_id, "same");

  settings.allow_mixed_builds = true;
  FarmMasterCore mixed(Payload(100), "run", 1, settings);
  mixed.OnHeartbeat(other, 0.0);
  EXPECT_EQ(mixed.workers_alive(), 1);
}

TEST(FarmMasterCore, EveryReadyWorkerGetsAJobBeforeAnyGetsASecond) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  for (int w = 0; w < 8; ++w) {
    m.OnHeartbeat(Beat(m, "w" + std::to_string(w)), 0.0);
  }
  m.StartBatch(Batch(8, 0), 0.0);
  const FarmOutbox out = m.Tick(0.0);
  ASSERT_EQ(out.jobs.size(), 8u);
  std::set<std::string> got;
  for (const auto& j : out.jobs) got.insert(j.worker_id);
  EXPECT_EQ(got.size(), 8u) << "8 jobs and 8 idle workers: one each";
  // With more jobs than workers the second round starts only after all
  // have one, and nobody gets more than slots + 1.
  FarmMasterCore m2(Payload(100), "run", 1, FarmSettings{});
  for (int w = 0; w < 3; ++w) {
    m2.OnHeartbeat(Beat(m2, "w" + std::to_string(w)), 0.0);
  }
  m2.StartBatch(Batch(10, 0), 0.0);
  std::map<std::string, int> per;
  for (const auto& j : m2.Tick(0.0).jobs) ++per[j.worker_id];
  EXPECT_EQ(per.size(), 3u);
  for (const auto& [id, n] : per) EXPECT_EQ(n, 2) << id;
}

opt_result_t Answer(const FarmMasterCore& m, const opt_job_t& job,
                    double seconds = 0.05) {
  opt_result_t r{};
  r.run_id = m.run_id();
  r.scenario_hash = m.scenario_hash();
  r.worker_id = job.worker_id;
  r.job_id = job.job_id;
  r.fitness = SimFitness(job.genome);
  r.eval_seconds = seconds;
  return r;
}

// Short episodes made the round trip between a result and the next job
// the workers' idle time: a busy worker holds its next job already.
TEST(FarmMasterCore, AWorkersNextJobIsSentBeforeItsCurrentOneFinishes) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  m.StartBatch(Batch(10, 0), 0.0);
  std::map<std::string, std::vector<opt_job_t>> held;
  for (const auto& j : m.Tick(0.0).jobs) held[j.worker_id].push_back(j);
  ASSERT_EQ(held["a"].size(), 2u) << "one to run, one queued";
  ASSERT_EQ(held["b"].size(), 2u);
  // a finishes its first: it gets another at once, still holding one.
  m.OnResult(Answer(m, held["a"][0]), 0.05);
  const FarmOutbox out = m.Tick(0.05);
  ASSERT_EQ(out.jobs.size(), 1u);
  EXPECT_EQ(out.jobs[0].worker_id, "a");
}

// Near a generation's end a job queued behind a slow episode would wait
// while another worker idles: with no more than one job per ready worker
// left, jobs wait at the master for the first worker to finish.
TEST(FarmMasterCore, TheLastRoundGoesToWhoeverFinishesFirst) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  for (int w = 0; w < 8; ++w)
    m.OnHeartbeat(Beat(m, "w" + std::to_string(w)), 0.0);
  m.StartBatch(Batch(16, 0), 0.0);
  std::map<std::string, opt_job_t> first;
  for (const auto& j : m.Tick(0.0).jobs) first[j.worker_id] = j;
  ASSERT_EQ(first.size(), 8u) << "one each, none queued";
  EXPECT_TRUE(m.Tick(0.01).jobs.empty());
  // w3 is fast: it takes two more while the others still run their first.
  m.OnResult(Answer(m, first["w3"]), 0.02);
  FarmOutbox out = m.Tick(0.02);
  ASSERT_EQ(out.jobs.size(), 1u);
  EXPECT_EQ(out.jobs[0].worker_id, "w3");
  m.OnResult(Answer(m, out.jobs[0]), 0.04);
  out = m.Tick(0.04);
  ASSERT_EQ(out.jobs.size(), 1u);
  EXPECT_EQ(out.jobs[0].worker_id, "w3");
}

TEST(FarmMasterCore, PrefetchedJobsOfAVanishedWorkerAreResentOnce) {
  FarmSettings settings;
  settings.worker_timeout = 2.0;
  FarmMasterCore m(Payload(100), "run", 1, settings);
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  m.StartBatch(Batch(6, 0), 0.0);
  std::map<std::string, std::vector<opt_job_t>> held;
  for (const auto& j : m.Tick(0.0).jobs) held[j.worker_id].push_back(j);
  ASSERT_EQ(held["a"].size(), 2u);
  // b keeps working and beating; a is never heard again.
  std::map<std::int64_t, int> sends;
  for (const auto& [w, jobs] : held) {
    for (const auto& j : jobs) ++sends[j.job_id];
  }
  std::vector<opt_job_t> b_jobs = held["b"];
  double t = 0.0;
  while (!m.batch_done() && t < 30.0) {
    t += 0.05;
    std::vector<std::int64_t> ids;
    for (const auto& j : b_jobs) ids.push_back(j.job_id);
    m.OnHeartbeat(Beat(m, "b", ids), t);
    if (!b_jobs.empty() && static_cast<int>(t * 20) % 4 == 0) {
      m.OnResult(Answer(m, b_jobs.front()), t);
      b_jobs.erase(b_jobs.begin());
    }
    for (const auto& j : m.Tick(t).jobs) {
      if (j.worker_id == "a") {
        // Overdue, asked again of a while it may only be slow; never once
        // it is gone.
        EXPECT_LT(t, settings.worker_timeout + 0.2) << "a is gone";
        continue;
      }
      if (std::find_if(b_jobs.begin(), b_jobs.end(), [&](const opt_job_t& h) {
            return h.job_id == j.job_id;
          }) != b_jobs.end()) {
        continue;  // asked again of the same worker: not a new send
      }
      ++sends[j.job_id];
      b_jobs.push_back(j);
    }
  }
  ASSERT_TRUE(m.batch_done());
  for (const auto& j : held["a"]) {
    EXPECT_EQ(sends[j.job_id], 2) << "sent to a, then once to b";
  }
  EXPECT_EQ(m.counters().jobs_resent, 2);
  EXPECT_EQ(m.workers_alive(), 1);
}

// One lost datagram (the job or its result) used to cost the job's
// deadline or a heartbeat and a second: with short episodes that was many
// generations' time.
TEST(FarmMasterCore, AnOverdueJobIsAskedAgainOfItsWorkerWithinEpisodes) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.StartBatch(Batch(3, 0), 0.0);
  std::vector<opt_job_t> jobs = m.Tick(0.0).jobs;
  ASSERT_EQ(jobs.size(), 2u);
  m.OnResult(Answer(m, jobs[0], 0.05), 0.05);  // the typical episode: 50 ms
  m.OnResult(Answer(m, jobs[1], 0.05), 0.1);
  const std::vector<opt_job_t> last = m.Tick(0.1).jobs;
  ASSERT_EQ(last.size(), 1u);
  // Its result is lost. Asked again of "a" after a few episodes' time,
  // long before the job deadline (2 s and more).
  double t = 0.1;
  std::vector<opt_job_t> again;
  while (again.empty() && t < 2.0) {
    t += 0.01;
    again = m.Tick(t).jobs;
  }
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].job_id, last[0].job_id);
  EXPECT_EQ(again[0].worker_id, "a") << "the same worker: no second episode";
  EXPECT_LT(t - 0.1, 0.05 + 3 * 0.05 + 0.05);
  EXPECT_EQ(m.counters().jobs_resent, 0);
  EXPECT_EQ(m.counters().jobs_poked, 1);
  // Then after twice as long, not at every check.
  double next = t;
  std::vector<opt_job_t> later;
  while (later.empty() && next < 5.0) {
    next += 0.01;
    later = m.Tick(next).jobs;
  }
  EXPECT_GT(next - t, 1.5 * (t - 0.1));
  m.OnResult(Answer(m, last[0]), next);
  EXPECT_TRUE(m.batch_done());
}

// A worker runs its jobs in order: the result of its second job says the
// first was lost (on the way there, or its result on the way back).
TEST(FarmMasterCore, AJobOvertakenByItsWorkersNextIsAskedAgainAtOnce) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.StartBatch(Batch(4, 0), 0.0);
  std::vector<opt_job_t> jobs = m.Tick(0.0).jobs;
  ASSERT_EQ(jobs.size(), 2u);  // one to run, one queued
  // Typical episode 50 ms, learnt from a first answer.
  m.OnResult(Answer(m, jobs[0], 0.05), 0.05);
  std::vector<opt_job_t> next = m.Tick(0.05).jobs;
  ASSERT_EQ(next.size(), 1u);
  // jobs[1] (queued at "a") or its result is lost; "a" runs next[0].
  m.OnResult(Answer(m, next[0], 0.05), 0.15);
  std::vector<opt_job_t> out = m.Tick(0.15).jobs;
  std::vector<std::int64_t> ids;
  for (const auto& j : out) ids.push_back(j.job_id);
  EXPECT_NE(std::find(ids.begin(), ids.end(), jobs[1].job_id), ids.end())
      << "not asked again when overtaken";
  EXPECT_EQ(m.counters().jobs_poked, 1);
  EXPECT_EQ(m.counters().jobs_resent, 0) << "the same worker, not another";
  // In order, nothing is asked twice.
  FarmMasterCore n(Payload(100), "run", 1, FarmSettings{});
  n.OnHeartbeat(Beat(n, "a"), 0.0);
  n.StartBatch(Batch(4, 0), 0.0);
  std::vector<opt_job_t> held = n.Tick(0.0).jobs;
  double t = 0.0;
  while (!n.batch_done() && !held.empty()) {
    t += 0.05;
    n.OnResult(Answer(n, held.front(), 0.05), t);
    held.erase(held.begin());
    for (const auto& j : n.Tick(t).jobs) held.push_back(j);
  }
  EXPECT_TRUE(n.batch_done());
  EXPECT_EQ(n.counters().jobs_poked, 0);
}

// A run's first jobs go out before any episode time is known: once one is,
// a lost first job is asked again within episodes, not at the job deadline.
TEST(FarmMasterCore, AFirstJobLostBeforeAnyEpisodeTimeIsAskedAgainSoon) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  m.StartBatch(Batch(2, 0), 0.0);
  const std::vector<opt_job_t> jobs = m.Tick(0.0).jobs;
  ASSERT_EQ(jobs.size(), 2u);
  m.OnResult(Answer(m, jobs[0], 0.05), 0.05);  // b's job is lost
  double t = 0.05;
  std::vector<opt_job_t> again;
  while (again.empty() && t < 5.0) {
    t += 0.01;
    again = m.Tick(t).jobs;
  }
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].job_id, jobs[1].job_id);
  EXPECT_EQ(again[0].worker_id, jobs[1].worker_id);
  EXPECT_LT(t, 0.5) << "the job deadline, not within episodes";
}

// Copies of each job and result on a small farm (a lost frame costs
// nothing), one on a large farm (where the datagrams would cost more).
TEST(FarmMasterCore, SmallFarmsSendTwoCopiesAndTellTheirWorkers) {
  FarmSettings settings;
  settings.duplicate_up_to = 4;
  FarmMasterCore m(Payload(100), "run", 1, settings);
  for (int w = 0; w < 4; ++w)
    m.OnHeartbeat(Beat(m, "w" + std::to_string(w)), 0.0);
  FarmOutbox out = m.Tick(0.0);
  EXPECT_EQ(out.copies, 2);
  ASSERT_EQ(out.runs.size(), 1u);
  EXPECT_EQ(out.runs[0].copies, 2);
  m.OnHeartbeat(Beat(m, "w4"), 0.1);
  out = m.Tick(1.0);
  EXPECT_EQ(out.copies, 1);
  ASSERT_EQ(out.runs.size(), 1u);
  EXPECT_EQ(out.runs[0].copies, 1);

  FarmWorkerCore w(WorkerSettings{}, "host", 1,
                   [](const std::string&, const std::string&) {
                     return std::make_shared<const Problem>();
                   });
  opt_run_t run = out.runs[0];
  run.copies = 2;
  w.OnRun(run, 0.0);
  EXPECT_EQ(w.Tick(0.0).copies, 2) << "results go out twice";
}

// A generation of thousands of jobs in one burst overflowed the receivers'
// socket buffers (docs/scaling.md): jobs go out in bursts of at most
// dispatch_burst, dispatch_rate a second, and the master asks to be woken
// when the next may go.
TEST(FarmMasterCore, ThousandsOfJobsGoOutInPacedBursts) {
  FarmSettings settings;
  settings.dispatch_burst = 256;
  settings.dispatch_rate = 25600;  // 256 per 10 ms
  FarmMasterCore m(Payload(100), "run", 1, settings);
  for (int w = 0; w < 1000; ++w) {
    m.OnHeartbeat(Beat(m, "w" + std::to_string(w)), 0.0);
  }
  // Three jobs a worker: one each, then one queued behind it each; the
  // third round waits for results.
  m.StartBatch(Batch(3000, 0), 0.0);
  EXPECT_EQ(m.Tick(0.0).jobs.size(), 256u);
  EXPECT_TRUE(m.Tick(0.0).jobs.empty()) << "no more at the same instant";
  EXPECT_NEAR(m.next_deadline(), 1.0 / 25600, 1e-9)
      << "woken when the next job may go";
  EXPECT_EQ(m.Tick(0.005).jobs.size(), 128u) << "half the period: half";
  std::set<std::string> workers;
  size_t sent = 256 + 128;
  double t = 0.005;
  while (sent < 2000 && t < 1.0) {
    t = std::max(m.next_deadline(), t + 0.01);  // a slow loop: 10 ms
    const FarmOutbox out = m.Tick(t);
    EXPECT_LE(out.jobs.size(), 256u) << "at " << t;
    for (const auto& j : out.jobs) workers.insert(j.worker_id);
    sent += out.jobs.size();
  }
  EXPECT_EQ(sent, 2000u) << "two rounds out within 2000 / 25600 s and a "
                            "loop's lag";
  EXPECT_LT(t, 0.1);
  EXPECT_EQ(workers.size(), 1000u);
}

// A small generation is not held back.
TEST(FarmMasterCore, AGenerationWithinTheBurstGoesOutAtOnce) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  for (int w = 0; w < 100; ++w) {
    m.OnHeartbeat(Beat(m, "w" + std::to_string(w)), 0.0);
  }
  m.StartBatch(Batch(300, 0), 0.0);
  EXPECT_EQ(m.Tick(0.0).jobs.size(), 200u) << "two rounds at once";
}

TEST(FarmMasterCore, OneHeartbeatNotListingAJobDoesNotResendIt) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  m.StartBatch(Batch(1, 0), 0.0);
  const FarmOutbox first = m.Tick(0.0);
  ASSERT_EQ(first.jobs.size(), 1u);
  const std::string owner = first.jobs[0].worker_id;
  const std::int64_t id = first.jobs[0].job_id;
  // A heartbeat that overtook the job: not listed once -> no re-send.
  m.OnHeartbeat(Beat(m, owner), 0.6);
  EXPECT_TRUE(m.Tick(0.6).jobs.empty());
  // Listed as done (the result is on its way): still no re-send.
  m.OnHeartbeat(Beat(m, owner, {}, {id}), 0.8);
  m.OnHeartbeat(Beat(m, owner, {}, {id}), 0.9);
  EXPECT_TRUE(m.Tick(0.9).jobs.empty());
  // The result never comes: the same worker is asked again (it answers
  // from memory) instead of another worker running the episode again.
  const FarmOutbox again = m.Tick(2.0);
  ASSERT_EQ(again.jobs.size(), 1u);
  EXPECT_EQ(again.jobs[0].worker_id, owner);
  EXPECT_EQ(m.counters().results_rerequested, 1);
  EXPECT_EQ(m.counters().jobs_resent, 0);
}

TEST(FarmMasterCore, TwoHeartbeatsNotListingAJobSendItElsewhere) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  m.StartBatch(Batch(1, 0), 0.0);
  const FarmOutbox first = m.Tick(0.0);
  ASSERT_EQ(first.jobs.size(), 1u);
  const std::string owner = first.jobs[0].worker_id;
  m.OnHeartbeat(Beat(m, owner), 0.6);
  m.OnHeartbeat(Beat(m, owner), 0.8);
  const FarmOutbox second = m.Tick(0.8);
  ASSERT_EQ(second.jobs.size(), 1u);
  EXPECT_NE(second.jobs[0].worker_id, owner);
  EXPECT_EQ(m.counters().jobs_resent, 1);
}

TEST(FarmMasterCore, LateDuplicateAndForeignResultsAreIgnored) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  const std::vector<Genome> batch = Batch(1, 0);
  m.StartBatch(batch, 0.0);
  const opt_job_t job = m.Tick(0.0).jobs.at(0);
  opt_result_t r{};
  r.run_id = "run";
  r.scenario_hash = m.scenario_hash();
  r.worker_id = "a";
  r.job_id = job.job_id;
  r.fitness = 4.0;
  opt_result_t foreign = r;
  foreign.run_id = "other";
  foreign.fitness = 1e9;
  m.OnResult(foreign, 0.5);
  EXPECT_FALSE(m.batch_done());
  m.OnResult(r, 1.0);
  ASSERT_TRUE(m.batch_done());
  r.fitness = 5.0;
  m.OnResult(r, 1.1);  // duplicate
  EXPECT_EQ(m.results()[0].fitness, 4.0);
  m.StartBatch(batch, 2.0);
  m.OnResult(r, 2.1);  // late: the previous batch's id
  EXPECT_FALSE(m.batch_done());
  EXPECT_EQ(m.counters().results_ignored, 3);
  opt_result_t nan = r;
  nan.job_id = m.Tick(2.1).jobs.at(0).job_id;
  nan.fitness = std::nan("");
  m.OnResult(nan, 2.2);
  EXPECT_EQ(m.counters().messages_malformed, 1);
  EXPECT_FALSE(m.batch_done());
}

// Islands keep two generations on the farm: the second batch's jobs wait
// behind the first's and go to whoever finishes early, results find their
// own batch, and a closed batch's late answers are ignored.
TEST(FarmMasterCore, AnOpenSecondBatchFeedsWorkersThatFinishTheFirstEarly) {
  constexpr double kEpisode = 5.0;  // s: no job is due a poke in this test
  FarmSettings settings;
  settings.extra_jobs_per_worker = 0;  // a job goes out when a worker frees
  FarmMasterCore m(Payload(100), "run", 1, settings);
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  const std::vector<Genome> first = Batch(2, 0), second = Batch(2, 1);
  const std::int64_t one = m.OpenBatch(first);
  const std::int64_t two = m.OpenBatch(second);
  const FarmOutbox out = m.Tick(0.0);
  ASSERT_EQ(out.jobs.size(), 2u) << "one job per idle worker";
  for (const opt_job_t& j : out.jobs) {
    EXPECT_EQ(j.generation, one) << "the older batch's jobs go out first";
  }
  // "a" finishes early while "b" still runs the first batch's slow one.
  const opt_job_t& fast =
      out.jobs[0].worker_id == "a" ? out.jobs[0] : out.jobs[1];
  const opt_job_t& slow =
      out.jobs[0].worker_id == "a" ? out.jobs[1] : out.jobs[0];
  m.OnResult(Answer(m, fast, kEpisode), 0.5);
  const FarmOutbox next = m.Tick(0.5);
  ASSERT_EQ(next.jobs.size(), 1u);
  EXPECT_EQ(next.jobs[0].worker_id, "a") << "the idle worker goes on";
  EXPECT_EQ(next.jobs[0].generation, two);
  EXPECT_FALSE(m.batch_done(one));
  m.OnResult(Answer(m, slow, kEpisode), 1.0);
  ASSERT_TRUE(m.batch_done(one));
  EXPECT_FALSE(m.batch_done(two));
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(m.results(one)[i].fitness, SimFitness(first[i]));
  }
  m.CloseBatch(one, 1.0);
  EXPECT_THROW(m.results(one), std::out_of_range);
  const long long ignored = m.counters().results_ignored;
  m.OnResult(Answer(m, slow, kEpisode),
             1.1);  // a duplicate of a closed batch's
  EXPECT_EQ(m.counters().results_ignored, ignored + 1);
  const FarmOutbox last = m.Tick(1.0);
  ASSERT_EQ(last.jobs.size(), 1u);
  EXPECT_EQ(last.jobs[0].worker_id, "b");
  m.OnResult(Answer(m, next.jobs[0], kEpisode), 1.2);
  m.OnResult(Answer(m, last.jobs[0], kEpisode), 1.3);
  ASSERT_TRUE(m.batch_done(two));
  for (size_t i = 0; i < second.size(); ++i) {
    EXPECT_EQ(m.results(two)[i].fitness, SimFitness(second[i]));
  }
}

// A job the workers say they cannot run fails the same way on each: it is
// tried again a few times (a worker may have lacked something), then the
// batch fails with the workers' reason instead of looping forever.
TEST(FarmMasterCore, AJobNoWorkerCanRunFailsTheBatchWithTheReason) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.StartBatch(Batch(1, 0), 0.0);
  opt_result_t r{};
  r.run_id = "run";
  r.scenario_hash = m.scenario_hash();
  r.worker_id = "a";
  r.error = "Kp: expected a value >= 0, got -4";
  double now = 0.0;
  for (int k = 0; k < FarmMasterCore::kMaxJobErrors; ++k) {
    EXPECT_EQ(m.failure(), "");
    const FarmOutbox out = m.Tick(now);
    ASSERT_FALSE(out.jobs.empty()) << "not sent again after error " << k;
    r.job_id = out.jobs.front().job_id;
    m.OnResult(r, now += 0.1);
    m.OnHeartbeat(Beat(m, "a"), now);
  }
  EXPECT_FALSE(m.batch_done());
  EXPECT_NE(m.failure().find("could not run job"), std::string::npos);
  EXPECT_NE(m.failure().find("Kp: expected a value >= 0"), std::string::npos)
      << m.failure();
  // A new batch starts clean.
  m.StartBatch(Batch(1, 1), now);
  EXPECT_EQ(m.failure(), "");
}

// Workers follow the newest master on a prefix: the older one is told why
// its workers left, once.
TEST(FarmMasterCore, WorkersTakenByAnotherRunOnThePrefixAreExplained) {
  std::vector<std::string> log;
  FarmSettings settings;
  settings.log = [&log](const std::string& line) { log.push_back(line); };
  FarmMasterCore m(Payload(100), "run", 1, settings);
  m.OnHeartbeat(Beat(m, "a"), 0.0);
  m.OnHeartbeat(Beat(m, "b"), 0.0);
  EXPECT_EQ(m.workers_ready(), 2);
  for (const char* id : {"a", "b"}) {
    opt_heartbeat_t other = Beat(m, id);
    other.run_id = "newer";
    m.OnHeartbeat(other, 0.1);
  }
  EXPECT_EQ(m.workers_ready(), 0);
  const auto said = std::count_if(log.begin(), log.end(), [](const auto& l) {
    return l.find("another mrsim-opt uses this prefix") != std::string::npos;
  });
  EXPECT_EQ(said, 1);
}

TEST(FarmMasterCore, DefaultChunkFitsOneEthernetFrame) {
  FarmMasterCore m(Payload(50000), "some-host-12345-1700000000", 1,
                   FarmSettings{});
  EXPECT_EQ(m.chunk_count(), (50000 + 1377) / 1378 + 0 * m.chunk_count())
      << "about 1378 bytes a chunk";
  opt_chunk_request_t req{};
  req.run_id = m.run_id();
  req.scenario_hash = m.scenario_hash();
  req.missing = {0};
  req.count = 1;
  m.OnChunkRequest(req, 0.0);
  const FarmOutbox out = m.Tick(0.0);
  ASSERT_EQ(out.chunks.size(), 1u);
  const int datagram =
      8 + static_cast<int>(FarmChannels(kDefaultFarmPrefix).chunk.size()) + 1 +
      out.chunks[0].getEncodedSize();
  EXPECT_LE(datagram, 1472);
  EXPECT_GE(datagram, 1400);
}

TEST(FarmMasterCore, HeartbeatsSlowDownAsTheFarmGrows) {
  FarmMasterCore m(Payload(100), "run", 1, FarmSettings{});
  m.OnHeartbeat(Beat(m, "w"), 0.0);
  EXPECT_DOUBLE_EQ(m.heartbeat_period(), 0.2);
  for (int w = 0; w < 1000; ++w) {
    m.OnHeartbeat(Beat(m, "w" + std::to_string(w)), 0.0);
  }
  EXPECT_GE(m.heartbeat_period(), 4.0);
  EXPECT_GT(m.worker_timeout(), 3 * m.heartbeat_period());
  const FarmOutbox out = m.Tick(0.0);
  ASSERT_EQ(out.runs.size(), 1u);
  EXPECT_EQ(out.runs[0].heartbeat_period, m.heartbeat_period());
}

TEST(FarmWorkerCore, FollowsARestartedMasterAtOnceKeepingItsPayload) {
  FarmWorkerCore w(WorkerSettings{}, "h", 1,
                   [](const std::string&, const std::string&) {
                     return std::make_shared<const Problem>();
                   });
  FarmMasterCore a(Payload(3000), "run-a", 100, FarmSettings{});
  for (const auto& m : a.Tick(0).runs) w.OnRun(m, 0.0);
  for (const auto& r : w.Tick(0.0).chunk_requests) a.OnChunkRequest(r, 0.0);
  for (const auto& c : a.Tick(0.0).chunks) w.OnChunk(c, 0.0);
  ASSERT_TRUE(w.ready());
  FarmMasterCore b(Payload(3000), "run-b", 200, FarmSettings{});
  // A late announcement of the dead master must not pull it back.
  for (const auto& m : b.Tick(0.1).runs) w.OnRun(m, 0.1);
  EXPECT_EQ(w.run_id(), "run-b");
  EXPECT_TRUE(w.ready()) << "same payload: nothing to fetch again";
  opt_run_t stale{};
  stale.run_id = "run-a";
  stale.started = 100;
  stale.scenario_hash = a.scenario_hash();
  stale.chunk_count = 3;
  w.OnRun(stale, 0.2);
  EXPECT_EQ(w.run_id(), "run-b");
}

// Worker "w" holding `m`'s payload, fetched through the protocol.
std::unique_ptr<FarmWorkerCore> ReadyWorker(FarmMasterCore& m) {
  WorkerSettings s;
  s.id = "w";
  auto w = std::make_unique<FarmWorkerCore>(
      s, "h", 1, [](const std::string&, const std::string&) {
        return std::make_shared<const Problem>();
      });
  for (const auto& x : m.Tick(0).runs) w->OnRun(x, 0.0);
  for (const auto& r : w->Tick(0.0).chunk_requests) m.OnChunkRequest(r, 0.0);
  for (const auto& c : m.Tick(0.0).chunks) w->OnChunk(c, 0.0);
  return w;
}

// Job `id` of `m`'s run, addressed to ReadyWorker's "w".
opt_job_t JobFor(const FarmMasterCore& m, std::int64_t id) {
  opt_job_t job{};
  job.run_id = m.run_id();
  job.scenario_hash = m.scenario_hash();
  job.worker_id = "w";
  job.job_id = id;
  return job;
}

TEST(FarmWorkerCore, AReAskedJobIsAnsweredFromMemoryNotRunAgain) {
  FarmMasterCore m(Payload(10), "run", 1, FarmSettings{});
  const std::unique_ptr<FarmWorkerCore> worker = ReadyWorker(m);
  ASSERT_TRUE(worker->ready());
  FarmWorkerCore& w = *worker;
  const opt_job_t job = JobFor(m, 42);
  w.OnJob(job, 0.1);
  w.OnJob(job, 0.1);  // a re-send of a queued job: one task
  const auto tasks = w.TakeTasks();
  ASSERT_EQ(tasks.size(), 1u);
  opt_result_t r{};
  r.run_id = "run";
  r.worker_id = "w";
  r.job_id = 42;
  w.OnEpisodeDone(r, 1.0);
  EXPECT_EQ(w.Tick(1.0).results.size(), 1u);
  w.OnJob(job, 2.0);
  EXPECT_TRUE(w.TakeTasks().empty());
  EXPECT_EQ(w.Tick(2.0).results.size(), 1u);
  EXPECT_EQ(w.counters().results_resent, 1);
  // The same id with another genome (a master that reused its run id) is
  // a new job, not a lost answer.
  opt_job_t other = job;
  other.genome = {1.0};
  other.gene_count = 1;
  w.OnJob(other, 2.1);
  EXPECT_EQ(w.TakeTasks().size(), 1u);
  // Its heartbeats list the job as done for a while.
  bool listed = false;
  for (const auto& hb : w.Tick(2.5).heartbeats) {
    for (auto id : hb.done) listed = listed || id == 42;
  }
  EXPECT_TRUE(listed);
}

// The pool takes one job beyond its threads, so a thread that ends an
// episode starts the next at once; the heartbeat lists both as held.
TEST(FarmWorkerCore, AJobHandedOutAheadIsHeldAndCanBeForgotten) {
  FarmMasterCore m(Payload(10), "run", 1, FarmSettings{});
  const std::unique_ptr<FarmWorkerCore> worker = ReadyWorker(m);
  ASSERT_TRUE(worker->ready());
  FarmWorkerCore& w = *worker;
  for (std::int64_t id : {1, 2, 3}) w.OnJob(JobFor(m, id), 0.1);
  EXPECT_EQ(w.TakeTasks().size(), 1u) << "one thread, nothing ahead";
  const auto ahead = w.TakeTasks(1);
  ASSERT_EQ(ahead.size(), 1u) << "one more, to wait in the pool";
  EXPECT_EQ(ahead[0].job_id, 2);
  EXPECT_TRUE(w.TakeTasks(1).empty());
  auto held = [&](double now) {
    std::set<std::int64_t> ids;
    for (const auto& hb : w.Tick(now).heartbeats) {
      ids.insert(hb.jobs.begin(), hb.jobs.end());
    }
    return ids;
  };
  EXPECT_EQ(held(1.0), (std::set<std::int64_t>{1, 2, 3}));
  w.Forget(2);  // its worker followed another run before starting it
  EXPECT_EQ(held(2.0), (std::set<std::int64_t>{1, 3}));
}

TEST(SimFarm, EightWorkersPopulationEightAllWork) {
  SimFarm farm(Payload(20000), FarmSettings{}, SimNetwork{});
  for (int w = 0; w < 8; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.RunUntil(3.0);
  RunAndCheck(farm, 10, 8);
  for (int w = 0; w < 8; ++w) {
    EXPECT_GE(farm.episodes_run_by("w" + std::to_string(w)), 9) << w;
  }
  EXPECT_EQ(farm.episodes_run(), 80);
}

TEST(SimFarm, JitterRunsNoEpisodeTwice) {
  SimNetwork net;
  net.delay = 0.020;
  net.jitter = 0.005;
  SimFarm farm(Payload(20000), FarmSettings{}, net);
  for (int w = 0; w < 8; ++w) farm.AddWorker("w" + std::to_string(w), 0.3);
  RunAndCheck(farm, 40, 8);
  EXPECT_LE(farm.episodes_run(), 320 * 102 / 100)
      << farm.master().counters().jobs_resent << " re-sent";
}

TEST(SimFarm, FivePercentLossKeepsEveryResult) {
  SimNetwork net;
  net.loss = 0.05;
  net.delay = 0.002;
  net.jitter = 0.001;
  SimFarm farm(Payload(60000), FarmSettings{}, net, 3);
  for (int w = 0; w < 6; ++w) farm.AddWorker("w" + std::to_string(w), 0.5);
  RunAndCheck(farm, 30, 12);
  EXPECT_GT(farm.master().counters().chunks_sent, farm.master().chunk_count())
      << "lost chunks were asked for again";
}

TEST(SimFarm, KilledAndAddedWorkersGiveEveryResult) {
  SimFarm farm(Payload(20000), FarmSettings{}, SimNetwork{});
  for (int w = 0; w < 6; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.At(5.5, [&] {
    farm.KillWorker("w0");
    farm.KillWorker("w1");
    farm.KillWorker("w2");
  });
  farm.At(7.0, [&] {
    farm.AddWorker("n0", 0.7);
    farm.AddWorker("n1", 0.7);
  });
  RunAndCheck(farm, 12, 8);
  EXPECT_GT(farm.episodes_run_by("n0"), 0);
  EXPECT_EQ(farm.master().workers_alive(), 5);
}

TEST(SimFarm, PartitionedWorkerIsDroppedAndRejoinsAfterHealing) {
  SimFarm farm(Payload(20000), FarmSettings{}, SimNetwork{});
  for (int w = 0; w < 4; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.At(4.2, [&] { farm.SetPartitioned("w3", true); });
  farm.At(20.0, [&] { farm.SetPartitioned("w3", false); });
  RunAndCheck(farm, 12, 8);
  const long long before = farm.episodes_run_by("w3");
  RunAndCheck(farm, 4, 8);
  EXPECT_GT(farm.episodes_run_by("w3"), before) << "w3 works again";
}

TEST(SimFarm, DeafWorkerGetsNoMoreJobsAndHealsByRejoining) {
  SimFarm farm(Payload(20000), FarmSettings{}, SimNetwork{});
  for (int w = 0; w < 4; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.RunUntil(2.0);
  farm.SetDeaf("w0", true);  // beats on, hears nothing
  const long long sent_before = farm.jobs_addressed_to("w0");
  RunAndCheck(farm, 3, 8);
  EXPECT_LE(farm.jobs_addressed_to("w0") - sent_before, 6);
  EXPECT_GE(farm.worker("w0").counters().rejoins, 1);
  const long long before = farm.episodes_run_by("w0");
  RunAndCheck(farm, 6, 8);
  EXPECT_GT(farm.episodes_run_by("w0"), before) << "healed by re-joining";
}

TEST(SimFarm, RestartedMasterIsFollowedAtOnce) {
  SimFarm farm(Payload(20000), FarmSettings{}, SimNetwork{});
  for (int w = 0; w < 4; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  RunAndCheck(farm, 2, 8);
  farm.StartMaster("run-2", 2000);
  const double restart = farm.now();
  farm.RunUntil(restart + 10.0,
                [&] { return farm.master().workers_ready() == 4; });
  EXPECT_LT(farm.now() - restart, 1.5) << "not after 3 s of silence";
  RunAndCheck(farm, 2, 8);
}

TEST(SimFarm, LostResultsAreAskedForNotRunAgain) {
  SimFarm farm(Payload(20000), FarmSettings{}, SimNetwork{});
  for (int w = 0; w < 2; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.RunUntil(2.0);
  farm.DropResults("w0", 3);
  RunAndCheck(farm, 3, 4);
  EXPECT_EQ(farm.episodes_run(), 12);
  // Asked again (a heartbeat listed them done, or they were overdue) and
  // answered from the worker's memory. (Three result datagrams dropped:
  // two results and the first copy of an answer from memory.)
  const long long asks = farm.master().counters().results_rerequested +
                         farm.master().counters().jobs_poked;
  EXPECT_GE(asks, 2);
  EXPECT_GE(farm.worker("w0").counters().results_resent, asks);
}

TEST(SimFarm, ThousandsOfSimulatedSecondsWithChurnAndLoss) {
  SimNetwork net;
  net.loss = 0.02;
  net.delay = 0.01;
  net.jitter = 0.005;
  SimFarm farm(Payload(30000), FarmSettings{}, net, 9);
  for (int w = 0; w < 10; ++w) farm.AddWorker("w" + std::to_string(w), 6.0);
  for (int k = 0; k < 20; ++k) {
    const double t = 100.0 * (k + 1);
    const std::string id = "w" + std::to_string(k % 10);
    farm.At(t, [&farm, id] { farm.KillWorker(id); });
    farm.At(t + 30, [&farm, id] { farm.AddWorker(id, 6.0); });
  }
  RunAndCheck(farm, 300, 10);
  EXPECT_GT(farm.now(), 1800.0);
}

TEST(SimFarm, AHundredWorkersAreFedWithoutIdling) {
  FarmSettings s;
  SimFarm farm(Payload(20000), s, SimNetwork{});
  for (int w = 0; w < 100; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.RunUntil(3.0);
  const double t0 = farm.now();
  RunAndCheck(farm, 5, 400);
  // 2000 one-second episodes on 100 workers: about 20 s when nobody idles.
  EXPECT_LT(farm.now() - t0, 20.0 * 1.15);
}

TEST(FarmVerify, LyingWorkerIsOutvotedDroppedAndItsResultsRedone) {
  std::vector<std::string> log;
  FarmSettings settings;
  settings.verify = 0.5;
  settings.log = [&](const std::string& line) { log.push_back(line); };
  SimFarm farm(Payload(2000), settings, SimNetwork{});
  farm.AddWorker("a", 1.0);
  farm.AddWorker("b", 1.0);
  farm.AddWorker("liar", 1.0);
  farm.SetLiar("liar", true);
  farm.RunUntil(3.0);
  // Every result is the genome's own, as a local run gives.
  RunAndCheck(farm, 4, 12);
  const FarmCounters& c = farm.master().counters();
  EXPECT_EQ(c.workers_dropped, 1);
  EXPECT_GE(c.results_verified, 1);
  EXPECT_EQ(farm.master().workers_alive(), 2);
  const auto said = std::count_if(log.begin(), log.end(), [](const auto& l) {
    return l.find("worker liar dropped for this run") != std::string::npos;
  });
  EXPECT_EQ(said, 1);
  // Dropped for good: no job reaches it after that.
  const long long jobs_to_liar = farm.jobs_addressed_to("liar");
  RunAndCheck(farm, 2, 12);
  EXPECT_EQ(farm.jobs_addressed_to("liar"), jobs_to_liar);
}

TEST(FarmVerify, LiarWhoseResultsWereTakenHasThemRedone) {
  // The liar answers first (it is faster), so some of its unverified
  // results are in the batch before a verified job catches it.
  FarmSettings settings;
  settings.verify = 0.25;
  SimFarm farm(Payload(2000), settings, SimNetwork{});
  farm.AddWorker("a", 1.0);
  farm.AddWorker("b", 1.0);
  farm.AddWorker("liar", 0.2);
  farm.SetLiar("liar", true);
  farm.RunUntil(3.0);
  RunAndCheck(farm, 1, 16);
  EXPECT_EQ(farm.master().counters().workers_dropped, 1);
  EXPECT_GE(farm.master().counters().results_redone, 1);
}

TEST(FarmVerify, HonestFarmVerifiesTheAskedShareAndDropsNobody) {
  FarmSettings settings;
  settings.verify = 0.25;
  SimFarm farm(Payload(2000), settings, SimNetwork{});
  for (int w = 0; w < 4; ++w) farm.AddWorker("w" + std::to_string(w), 1.0);
  farm.RunUntil(3.0);
  RunAndCheck(farm, 2, 16);
  EXPECT_EQ(farm.master().counters().results_verified, 8);  // 32 x 0.25
  EXPECT_EQ(farm.master().counters().workers_dropped, 0);
  EXPECT_EQ(farm.episodes_run(), 40);
}

TEST(FarmVerify, WithoutVerifyALiarGoesUnnoticed) {
  // What the test harness's liar does to an unverified farm.
  SimFarm farm(Payload(2000), FarmSettings{}, SimNetwork{});
  farm.AddWorker("a", 1.0);
  farm.AddWorker("liar", 1.0);
  farm.SetLiar("liar", true);
  farm.RunUntil(3.0);
  const std::vector<Genome> batch = Batch(8, 0);
  std::vector<EvalResult> results;
  ASSERT_TRUE(farm.Evaluate(batch, 600, &results));
  int wrong = 0;
  for (size_t i = 0; i < batch.size(); ++i) {
    wrong += results[i].fitness != SimFitness(batch[i]);
  }
  EXPECT_GT(wrong, 0);
}

}  // namespace
}  // namespace mrsim
