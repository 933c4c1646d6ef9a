// bench_farm_net: the farm over namespace "hosts" behind a bridge
// (tests/farm_net/farm_rig.h). The master is this process, moved into the
// rig's master namespace; workers are real mrsim-worker processes (capped
// to 0.2 CPU) or protocol-only fake workers.
//   farm_net_efficiency_8w   evaluations/s over workers / mean episode time
//                            with two islands in flight (also _pop8, and
//                            _long: ~1 s episodes); _one_island: each
//                            generation waits for the one before
//   farm_loss5_slowdown      wall time with 5% frame loss over without
//                            (median of three alternating pairs)
//   farm_jitter_duplicates   fraction of episodes run twice, 20 ms +-5 ms
//                            (simulated network: the kernel has no netem)
//   farm_net_jitter_duplicates  the same on the rig: real workers whose
//                            ports delay every frame 20 ms +-5 ms through
//                            the rig's user-space relay (delay_relay.h)
//   farm_master_cpu_1000w    the master's share of a core, 1,000 fake
//                            workers, 1 s episodes
//   farm_throughput_1000w    evaluations/s over 1,000 / 1 s
//   farm_master_cpu_10000w   the same with 10,000 fake workers in 10
//   farm_throughput_10000w   processes and 10 s episodes
#include <fcntl.h>
#include <fmt/format.h>
#include <sched.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/lcm_url.h"
#include "gait_controller/gait_presets.h"
#include "optimizer/episode/episode.h"
#include "optimizer/episode/episode_physics_pool.h"
#include "optimizer/farm/farm_evaluator.h"
#include "optimizer/farm/farm_worker.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/search/random.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/farm_net/farm_rig.h"
#include "tests/optimizer/sim_farm.h"

namespace {

// The simulations the benchmark's episodes share, as mrsim-opt's threads do.
mrsim::EpisodePhysicsPool& Physics() {
  static mrsim::EpisodePhysicsPool pool;
  return pool;
}

using Clock = std::chrono::steady_clock;
using mrsim::testing::ChildProcess;
using mrsim::testing::FarmRig;
constexpr const char* kUrl = "udpm://239.255.76.67:7667?ttl=1";

double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double CpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec +
         1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

mrsim::Problem SnakeProblem(double episode) {
  mrsim::Problem p;
  p.scenario = mrsim::ReadScenarioFile(std::string(MRSIM_SOURCE_DIR) +
                                       "/scenarios/snake11.xml");
  p.genome = mrsim::ReadGenomeFile(std::string(MRSIM_SOURCE_DIR) +
                                   "/scenarios/forward_gait.genome.xml");
  p.episode.duration = episode;
  p.episode.base_gait = *mrsim::FindGaitPreset("forward");
  return mrsim::DecodeProblem(mrsim::EncodeProblem(p), "bench");
}

std::vector<mrsim::Genome> RandomBatch(const mrsim::GenomeSpec& spec, int n,
                                       std::uint64_t seed) {
  mrsim::Random random(seed);
  std::vector<mrsim::Genome> batch;
  for (int i = 0; i < n; ++i) batch.push_back(spec.RandomGenome(random));
  return batch;
}

// Moves this thread (the master: LCM opens its sockets here) into a
// namespace, back again on destruction.
class InNamespace {
 public:
  explicit InNamespace(const std::string& ns)
      : home_(open("/proc/self/ns/net", O_RDONLY)) {
    const int fd = open(("/var/run/netns/" + ns).c_str(), O_RDONLY);
    if (fd < 0 || setns(fd, CLONE_NEWNET) != 0) {
      throw std::runtime_error("cannot enter namespace " + ns);
    }
    close(fd);
  }
  ~InNamespace() {
    setns(home_, CLONE_NEWNET);
    close(home_);
  }

 private:
  int home_;
};

std::string NsOf(const FarmRig& rig, int node) {
  return rig.In(node, {}).back();  // ".. ip netns exec <ns>"
}

// CPU seconds the worker processes ran, all threads and their episode
// threads alone (/proc/PID/task/TID/schedstat, in nanoseconds).
struct WorkerCpu {
  double total = 0, episodes = 0;
};

WorkerCpu ReadWorkerCpu(const std::vector<int>& pids) {
  WorkerCpu cpu;
  for (int pid : pids) {
    std::error_code ec;
    for (const auto& task : std::filesystem::directory_iterator(
             fmt::format("/proc/{}/task", pid), ec)) {
      std::ifstream stat(task.path() / "schedstat");
      std::ifstream comm(task.path() / "comm");
      double ns = 0;
      std::string name;
      if (!(stat >> ns)) continue;
      std::getline(comm, name);
      cpu.total += ns * 1e-9;
      if (name == mrsim::FarmWorker::kEpisodeThreadName) {
        cpu.episodes += ns * 1e-9;
      }
    }
  }
  return cpu;
}

struct Measure {
  double wall = 0, episodes = 0, cpu = 0;
  WorkerCpu workers;  // during the measured batches
  int jobs = 0;
  mrsim::FarmCounters counters;
  long long accepted_total = 0;  // results, the warm-up batch included
  int gone = 0, requeued = 0;    // master events during the measured batches
};

// The kernel's UDP counters of a node's namespace (/proc/net/snmp is per
// namespace): received datagrams and receive-buffer drops.
std::string UdpCounters(const FarmRig& rig, int node) {
  const std::string cmd =
      "ip netns exec " + NsOf(rig, node) +
      " awk '/^Udp:/{n++} /^Udp:/&&n==2{print \"in\", $2, \"rcvbuf_errors\", "
      "$6}' /proc/net/snmp";
  std::string out;
  if (FILE* f = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof buf, f)) out += buf;
    pclose(f);
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

// Runs `batches` batches of `population` on a ready farm (after a warm-up
// batch that fetches the payload), `islands` of them in flight at once as
// mrsim-opt --islands keeps them (1: each waits for the one before).
Measure RunFarm(FarmRig& rig, const mrsim::Problem& problem, int population,
                int batches, int islands = 1,
                const std::vector<int>& worker_pids = {}) {
  static int runs = 0;
  InNamespace in(NsOf(rig, 0));
  mrsim::FarmSettings settings;
  Measure m;
  bool counting = false;
  settings.log = [&](const std::string& line) {
    if (!counting) return;
    if (line.find(" is gone") != std::string::npos) ++m.gone;
    if (line.find(" re-queued") != std::string::npos) {
      ++m.requeued;
      fmt::print(stderr, "farm: {}\n", line);  // rare: say why
    }
  };
  mrsim::FarmEvaluator farm(std::string(kUrl), mrsim::EncodeProblem(problem),
                            fmt::format("bench-{}-{}", getpid(), ++runs),
                            settings);
  // Until every worker holds the payload, then once more so each has run a
  // job: a worker still fetching would be missing from the measured run.
  const int workers = rig.nodes() - 1;
  for (int k = 0; k < 100 && farm.workers_ready() < workers; ++k) {
    farm.Evaluate(RandomBatch(problem.genome, population, 1));
  }
  farm.Evaluate(RandomBatch(problem.genome, population, 1));
  counting = true;
  const mrsim::FarmCounters c0 = farm.counters();
  const double before = farm.episode_seconds();
  const double cpu0 = CpuSeconds();
  const WorkerCpu workers0 = ReadWorkerCpu(worker_pids);
  const auto t0 = Clock::now();
  int submitted = 0;
  for (; submitted < std::min(islands, batches); ++submitted) {
    farm.Submit(RandomBatch(problem.genome, population, 2 + submitted));
  }
  for (int b = 0; b < batches; ++b) {
    farm.Collect();
    m.jobs += population;
    if (submitted < batches) {
      farm.Submit(RandomBatch(problem.genome, population, 2 + submitted++));
    }
  }
  m.wall = Since(t0);
  m.cpu = CpuSeconds() - cpu0;
  const WorkerCpu workers1 = ReadWorkerCpu(worker_pids);
  m.workers.total = workers1.total - workers0.total;
  m.workers.episodes = workers1.episodes - workers0.episodes;
  m.episodes = farm.episode_seconds() - before;
  counting = false;
  const mrsim::FarmCounters& c = farm.counters();
  m.counters.jobs_sent = c.jobs_sent - c0.jobs_sent;
  m.counters.jobs_resent = c.jobs_resent - c0.jobs_resent;
  m.counters.results_accepted = c.results_accepted - c0.results_accepted;
  m.counters.results_ignored = c.results_ignored - c0.results_ignored;
  m.counters.jobs_poked = c.jobs_poked - c0.jobs_poked;
  m.counters.busiest_worker_seconds =
      c.busiest_worker_seconds - c0.busiest_worker_seconds;
  m.counters.heartbeats_received =
      c.heartbeats_received - c0.heartbeats_received;
  m.counters.messages_received = c.messages_received - c0.messages_received;
  m.accepted_total = c.results_accepted;
  return m;
}

// The most any dispatcher could reach on `workers` equal workers with the
// episodes of these batches, from each genome's own cost (CPU seconds of
// its episode here, best of 3): a generation takes at least its longest
// episode and at least its total over the workers. Below 1 when the
// genomes' costs differ (a robot curled on itself has more contacts to
// solve than one lying flat), whatever the network and the farm do.
double GenomeBound(const mrsim::Problem& problem, int population, int batches,
                   int workers) {
  const auto thread_cpu = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  };
  double work = 0, span = 0;
  for (int b = 0; b < batches; ++b) {
    double sum = 0, longest = 0;
    for (const mrsim::Genome& g :
         RandomBatch(problem.genome, population, 2 + b)) {
      double best = 1e9;
      for (int r = 0; r < 3; ++r) {
        const double t0 = thread_cpu();
        mrsim::RunEpisode(problem, g, {}, &Physics());
        best = std::min(best, thread_cpu() - t0);
      }
      sum += best;
      longest = std::max(longest, best);
    }
    work += sum;
    span += std::max(longest, sum / workers);
  }
  return work / (workers * span);
}

void Efficiency() {
  const int workers = 8;
  // Episodes of 1 simulated second take ~0.01 s of CPU, ~0.05 s at 0.2 of
  // a CPU: enough generations that one lost datagram or one slow episode
  // is not the whole figure, nor the first and last generation's (the
  // pipeline filling and draining) with islands.
  const int kBatches = 24;
  const double cap = 0.2;
  FarmRig rig(workers + 1);
  std::vector<std::unique_ptr<ChildProcess>> ws;
  std::vector<int> pids;
  for (int k = 1; k <= workers; ++k) {
    ws.push_back(std::make_unique<ChildProcess>(rig.In(
        k, {std::string(MRSIM_BINARY_DIR) + "/optimizer/process/mrsim-worker",
            "--lcm-url", kUrl, "--id", fmt::format("w{}", k), "--quiet"})));
    rig.CapCpu(ws.back()->pid(), cap);
    pids.push_back(ws.back()->pid());
  }
  const auto report = [&](const std::string& name, const Measure& m,
                          int islands = 1) {
    const double mean_episode = m.episodes / m.jobs;
    const double efficiency = (m.jobs / m.wall) / (workers / mean_episode);
    // efficiency = barrier x latency: what the generation barrier allows
    // with these episodes, and the share of that the farm reached.
    // (With two islands no generation waits for another: no barrier.)
    const double busiest = m.counters.busiest_worker_seconds;
    fmt::print(
        stderr,
        "farm 8w {}: {} jobs in {:.2f} s, mean episode {:.3f} s, {} "
        "sent ({} re-sent, {} asked again), {} results ignored{}\n",
        name, m.jobs, m.wall, mean_episode, m.counters.jobs_sent,
        m.counters.jobs_resent, m.counters.jobs_poked,
        m.counters.results_ignored,
        islands > 1
            ? fmt::format("; {} islands", islands)
            : fmt::format("; barrier bound {:.3f}, busiest worker "
                          "busy {:.3f} of the wall time",
                          m.episodes / (workers * busiest), busiest / m.wall));
    fmt::print("BENCH {} {:.3f} ratio\n", name, efficiency);
    if (m.workers.total > 0) {
      fmt::print(stderr,
                 "farm 8w {}: workers ran {:.2f} CPU-s ({:.3f} of their "
                 "caps), {:.3f} of it in episode threads\n",
                 name, m.workers.total,
                 m.workers.total / (workers * cap * m.wall),
                 m.workers.episodes / m.workers.total);
      fmt::print("BENCH {}_cpu {:.3f} ratio\n", name,
                 m.workers.episodes / (workers * cap * m.wall));
    }
    std::fflush(stdout);
  };
  const mrsim::Problem problem = SnakeProblem(1.0);
  for (int population : {8, 16}) {
    const std::string name = population == 8 ? "farm_net_efficiency_8w_pop8"
                                             : "farm_net_efficiency_8w";
    // As mrsim-opt --islands 2 runs: the next generation is on the farm
    // while one's last episodes run.
    report(name, RunFarm(rig, problem, population, kBatches, 2, pids), 2);
    // One population: each generation waits for its slowest episode.
    report(name + "_one_island",
           RunFarm(rig, problem, population, kBatches, 1, pids));
    // That wait's ceiling, from the genomes themselves (the same batches).
    fmt::print("BENCH {}_genome_bound {:.3f} ratio\n", name,
               GenomeBound(problem, population, kBatches, workers));
    std::fflush(stdout);
  }
  // The setting the target was set in: ~1 s episodes (then 1 simulated s
  // at 0.2 CPU; now 20 simulated s).
  const mrsim::Problem long_problem = SnakeProblem(20.0);
  report("farm_net_efficiency_8w_long",
         RunFarm(rig, long_problem, 16, 4, 2, pids), 2);
  // Clean and lossy alternately, the median of three pairs: one pair's
  // runs last ~2 s each, and on a shared machine two clean runs already
  // differ by 10%, the size of the effect measured.
  std::vector<double> slowdowns;
  for (int pair = 0; pair < 3; ++pair) {
    const Measure clean = RunFarm(rig, problem, 16, kBatches);
    rig.SetLoss(5);
    const Measure lossy = RunFarm(rig, problem, 16, kBatches);
    rig.SetLoss(0);
    fmt::print(stderr,
               "farm 8w loss: clean {:.2f} s for {:.2f} episode-s; 5% loss "
               "{:.2f} s for {:.2f} episode-s ({} re-sent, {} asked again)\n",
               clean.wall, clean.episodes, lossy.wall, lossy.episodes,
               lossy.counters.jobs_resent, lossy.counters.jobs_poked);
    // Per episode-second, so slower or faster episodes do not count.
    slowdowns.push_back((lossy.wall / lossy.episodes) /
                        (clean.wall / clean.episodes));
  }
  std::sort(slowdowns.begin(), slowdowns.end());
  fmt::print("BENCH farm_loss5_slowdown {:.3f} ratio\n", slowdowns[1]);
}

void JitterDuplicates() {
  mrsim::testing::SimNetwork net;
  net.delay = 0.020;
  net.jitter = 0.005;
  mrsim::testing::SimFarm farm(std::string(30000, 'x'), mrsim::FarmSettings{},
                               net);
  for (int w = 0; w < 8; ++w) farm.AddWorker(fmt::format("w{}", w), 0.3);
  std::vector<mrsim::EvalResult> out;
  long long jobs = 0;
  for (int g = 0; g < 41; ++g) {
    std::vector<mrsim::Genome> batch(8, mrsim::Genome{1.0 * g});
    if (!farm.Evaluate(batch, 600, &out)) throw std::runtime_error("stuck");
    jobs += 8;
  }
  fmt::print("BENCH farm_jitter_duplicates {:.4f} fraction\n",
             static_cast<double>(farm.episodes_run() - jobs) / jobs);
  std::fflush(stdout);

  // The same on real processes: 8 workers at 0.2 CPU, every worker's port
  // 20 ms +- 5 ms, each frame on its own draw. Episodes run = the workers'
  // "jobs done" (printed when they stop), against the results the master
  // accepted (each job once).
  const int workers = 8;
  mrsim::testing::RigOptions options;
  options.delays.assign(workers + 1, mrsim::testing::LinkDelay{0.020, 0.005});
  options.delays[0] = {};  // the master's port
  options.seed = 14;
  FarmRig rig(workers + 1, options);
  std::vector<std::unique_ptr<ChildProcess>> ws;
  for (int k = 1; k <= workers; ++k) {
    ws.push_back(std::make_unique<ChildProcess>(
        rig.In(k, {std::string(MRSIM_BINARY_DIR) +
                       "/optimizer/process/mrsim-worker",
                   "--lcm-url", kUrl, "--id", fmt::format("w{}", k)}),
        fmt::format("/tmp/bench_farm_net_jitter_w{}.log", k)));
    rig.CapCpu(ws.back()->pid(), 0.2);
  }
  const Measure m = RunFarm(rig, SnakeProblem(1.0), 16, 12);
  long long ran = 0;
  for (auto& w : ws) {
    w->Stop();
    const std::string out = w->Output();
    const size_t at = out.rfind("stopping; ");
    if (at == std::string::npos) {
      throw std::runtime_error("a worker did not say how many jobs it did: " +
                               out);
    }
    ran += std::atoll(out.c_str() + at + 10);
  }
  const mrsim::testing::RelayCounters relay = rig.relay_counters();
  fmt::print(stderr,
             "farm 8w jitter: {} results accepted, {} episodes run, {} "
             "re-sent, {} asked again; relay {} frames, {} overtook, {} "
             "overflowed\n",
             m.accepted_total, ran, m.counters.jobs_resent,
             m.counters.jobs_poked, relay.frames, relay.reordered,
             relay.overflowed);
  fmt::print("BENCH farm_net_jitter_duplicates {:.4f} fraction\n",
             static_cast<double>(ran - m.accepted_total) / m.accepted_total);
}

// `processes` x `per` protocol-only workers with `episode` s fake
// episodes, two generations of two rounds each; prints
// farm_master_cpu_<N>w and farm_throughput_<N>w.
void ManyWorkers(int processes, int per, double episode) {
  const int total = processes * per;
  const std::string tag = fmt::format("{}w", total);
  const mrsim::Problem problem = SnakeProblem(1.0);
  FarmRig rig(processes + 1);
  // The figure depends on the receive buffer the kernel allows
  // (docs/scaling.md): 4 MB for this run, as the farm asks.
  const std::int64_t rmem =
      rig.RaiseReceiveBufferMax(mrsim::FarmLink::kReceiveBuffer);
  if (rmem > 0 && rmem < mrsim::FarmLink::kReceiveBuffer) {
    fmt::print(
        "bench_farm_net: net.core.rmem_max raised from {} to {} bytes for "
        "this run (restored after)\n",
        rmem, mrsim::KernelReceiveBufferMax());
  }
  std::vector<std::unique_ptr<ChildProcess>> ws;
  for (int k = 1; k <= processes; ++k) {
    ws.push_back(std::make_unique<ChildProcess>(
        rig.In(k, {std::string(MRSIM_BINARY_DIR) +
                       "/optimizer/process/mrsim-worker",
                   "--lcm-url", kUrl, "--id", fmt::format("f{}", k),
                   "--fake-episode", fmt::format("{}", episode),
                   "--fake-workers", std::to_string(per)}),
        fmt::format("/tmp/bench_farm_net_f{}.log", k)));
  }
  std::vector<std::string> udp0;
  for (int k = 0; k <= processes; ++k) udp0.push_back(UdpCounters(rig, k));
  const Measure m = RunFarm(rig, problem, total * 2, 2);
  // What went where (stderr: the BENCH lines stay on stdout).
  fmt::print(stderr, "farm {}: net.core.rmem_max {} bytes\n", tag,
             mrsim::KernelReceiveBufferMax());
  fmt::print(stderr,
             "farm {}: {:.1f} s, {} jobs sent ({} re-sent), {} results, "
             "{} heartbeats and {} messages received by the master, {} "
             "workers declared gone, {} re-queues\n",
             tag, m.wall, m.counters.jobs_sent, m.counters.jobs_resent,
             m.counters.results_accepted, m.counters.heartbeats_received,
             m.counters.messages_received, m.gone, m.requeued);
  for (int k = 0; k <= processes; ++k) {
    fmt::print(stderr, "farm {}: node {} udp before [{}] after [{}]\n", tag, k,
               udp0[static_cast<size_t>(k)], UdpCounters(rig, k));
  }
  ws.clear();  // stopped: their logs end with their counters
  for (int k = 1; k <= processes; ++k) {
    std::ifstream log(fmt::format("/tmp/bench_farm_net_f{}.log", k));
    std::string line, last;
    while (std::getline(log, line)) {
      if (line.find("stopping;") != std::string::npos) last = line;
    }
    fmt::print(stderr, "farm {}: {}\n", tag, last);
  }
  fmt::print("BENCH farm_master_cpu_{} {:.3f} core\n", tag, m.cpu / m.wall);
  fmt::print("BENCH farm_throughput_{} {:.3f} ratio\n", tag,
             (m.jobs / m.wall) / (total / episode));
}

}  // namespace

int main(int argc, char** argv) {
  // bench_farm_net [jitter|efficiency|thousand|tenthousand]...: only those
  // cases.
  const std::vector<std::string> only(argv + 1, argv + argc);
  const auto want = [&](const std::string& name) {
    return only.empty() ||
           std::find(only.begin(), only.end(), name) != only.end();
  };
  std::string why;
  if (!FarmRig::Available(&why)) {
    fmt::print("bench_farm_net: skipped: {}\n", why);
    return 0;
  }
  try {
    FarmRig::CleanupStale();
    if (want("jitter")) JitterDuplicates();
    std::fflush(stdout);
    if (want("efficiency")) Efficiency();
    std::fflush(stdout);
    if (want("thousand")) ManyWorkers(4, 250, 1.0);
    std::fflush(stdout);
    if (want("tenthousand")) ManyWorkers(10, 1000, 10.0);
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_farm_net: {}\n", e.what());
    return 1;
  }
  return 0;
}
