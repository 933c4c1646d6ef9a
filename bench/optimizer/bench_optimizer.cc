// bench_optimizer: (1) farm evaluations/s with 1 and 2 mrsim-worker
// processes and the master's overhead per evaluation against the episode's
// own time; (2) the optimised forward gait of the 11-module snake against
// the `forward` preset, 20 s episodes, the same budget for GA, SA, PSO and
// random search. LCM ports 7920-7929.
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <vector>

#include "gait_controller/gait_presets.h"
#include "optimizer/episode.h"
#include "optimizer/farm/farm_evaluator.h"
#include "optimizer/local_evaluator.h"
#include "optimizer/optimization_run.h"
#include "optimizer/problem_codec.h"
#include "sim_core/scenario_xml.h"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A worker process, killed and reaped on destruction.
class Worker {
 public:
  Worker(const std::string& url, const std::string& id) {
    const std::string exe =
        std::string(MRSIM_BINARY_DIR) + "/optimizer/process/mrsim-worker";
    std::vector<std::string> args = {exe,    "--lcm-url", url,
                                     "--id", id,          "--quiet"};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, exe.c_str(), nullptr, nullptr, argv.data(),
                    environ) != 0) {
      throw std::runtime_error("cannot start " + exe);
    }
  }
  ~Worker() {
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

 private:
  pid_t pid_ = -1;
};

mrsim::Problem SnakeProblem(double episode) {
  mrsim::Problem p;
  p.scenario = mrsim::ReadScenarioFile(std::string(MRSIM_SOURCE_DIR) +
                                       "/scenarios/snake11.xml");
  p.genome = mrsim::ReadGenomeFile(std::string(MRSIM_SOURCE_DIR) +
                                   "/scenarios/forward_gait.genome.xml");
  p.episode.duration = episode;
  p.episode.base_gait = *mrsim::FindGaitPreset("forward");
  // Round trip, as mrsim-opt does, so every evaluator sees the same bytes.
  return mrsim::DecodeProblem(mrsim::EncodeProblem(p), "bench");
}

std::vector<mrsim::Genome> RandomBatch(const mrsim::GenomeSpec& spec, int n,
                                       std::uint64_t seed) {
  mrsim::Random random(seed);
  std::vector<mrsim::Genome> batch;
  for (int i = 0; i < n; ++i) batch.push_back(spec.RandomGenome(random));
  return batch;
}

struct FarmMeasure {
  double evals_per_second = 0;
  double overhead_percent = 0;
  double episode_wall = 0;  // mean wall time of one episode on a worker
};

FarmMeasure MeasureFarm(int workers, int port, int jobs) {
  const std::string url = fmt::format("udpm://239.255.76.67:{}?ttl=0", port);
  const mrsim::Problem problem = SnakeProblem(4.0);
  lcm::LCM lcm(url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM " + url);
  std::vector<std::unique_ptr<Worker>> pool;
  for (int w = 0; w < workers; ++w) {
    pool.push_back(std::make_unique<Worker>(url, fmt::format("bench{}", w)));
  }
  mrsim::FarmSettings settings;
  mrsim::FarmEvaluator farm(lcm, mrsim::EncodeProblem(problem),
                            fmt::format("bench-{}-{}", workers, getpid()),
                            settings);
  // Warm up until every worker holds the payload and has run a job.
  farm.Evaluate(RandomBatch(problem.genome, 2 * workers, 1));
  const double before = farm.episode_seconds();
  const auto t0 = Clock::now();
  farm.Evaluate(RandomBatch(problem.genome, jobs, 2));
  const double wall = Since(t0);
  const double episodes = farm.episode_seconds() - before;
  FarmMeasure m;
  m.evals_per_second = jobs / wall;
  // Wall time per worker beyond its own episodes, per evaluation.
  m.overhead_percent = 100.0 * (wall * workers - episodes) / episodes;
  m.episode_wall = episodes / jobs;
  return m;
}

// The same batch on local threads: how far this machine lets two episodes
// run in parallel at all (context for the farm's ratio).
double LocalRate(int threads, int jobs) {
  const mrsim::Problem problem = SnakeProblem(4.0);
  mrsim::LocalEvaluator local(
      [&](const mrsim::Genome& g) { return mrsim::RunEpisode(problem, g); },
      threads);
  const auto batch = RandomBatch(problem.genome, jobs, 2);
  const auto t0 = Clock::now();
  local.Evaluate(batch);
  return jobs / Since(t0);
}

double Speed(const mrsim::EvalResult& r) { return r.speed; }

}  // namespace

int main(int argc, char** argv) {
  // --farm-only: just the farm figures (quick look while tuning).
  const bool farm_only = argc > 1 && std::string(argv[1]) == "--farm-only";
  try {
    // Farm: same batch of 4 s episodes on 1 and on 2 workers.
    const int jobs = 16;
    const FarmMeasure one = MeasureFarm(1, 7920, jobs);
    const FarmMeasure two = MeasureFarm(2, 7921, jobs);
    std::printf(
        "# farm: %d episodes of 4 s: %.2f evals/s on 1 worker, %.2f "
        "on 2 (%u cores); one episode takes %.3f s on a lone worker, %.3f s "
        "with two workers running\n",
        jobs, one.evals_per_second, two.evals_per_second,
        std::thread::hardware_concurrency(), one.episode_wall,
        two.episode_wall);
    const double local1 = LocalRate(1, jobs), local2 = LocalRate(2, jobs);
    std::printf(
        "# same batch on local threads: %.2f evals/s on 1, %.2f on 2 "
        "(%.2f x: what this machine allows right now)\n",
        local1, local2, local2 / local1);
    std::printf("BENCH farm_speedup_2w %.3f x\n",
                two.evals_per_second / one.evals_per_second);
    std::printf("BENCH farm_overhead %.3f %%\n", one.overhead_percent);
    std::fflush(stdout);

    if (farm_only) return 0;

    // Optimised gait vs the preset: 20 s episodes, same budget each.
    const mrsim::Problem problem = SnakeProblem(20.0);
    const mrsim::EvalResult preset =
        mrsim::RunEpisode(problem, problem.genome.StartGenome());
    const int population = 8, generations = 6;
    std::printf(
        "# forward preset: %.4f m/s over 20 s; budget per algorithm: "
        "%d generations x %d (random start, no preset in the "
        "population), seed 1\n",
        Speed(preset), generations, population);
    std::fflush(stdout);
    for (const char* algo : {"ga", "sa", "pso", "random"}) {
      mrsim::AlgorithmSettings a;
      a.algorithm = algo;
      a.population = population;
      a.seed = 1;
      a.include_start = false;
      mrsim::LocalEvaluator evaluator(
          [&](const mrsim::Genome& g) { return mrsim::RunEpisode(problem, g); },
          static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
      mrsim::RunOptions options;
      options.generations = generations;
      const auto t0 = Clock::now();
      const mrsim::RunResult r =
          mrsim::RunOptimization(problem.genome, a, evaluator, options);
      std::string genes;
      for (int i = 0; i < problem.genome.size(); ++i) {
        if (problem.genome.genes[i].enabled) {
          genes += fmt::format(" {}={:.3f}", problem.genome.genes[i].name,
                               r.best[i]);
        }
      }
      std::printf("# %s: best %.4f m/s (generation %d, %s) in %.0f s\n", algo,
                  Speed(r.best_result), r.best_generation, genes.c_str(),
                  Since(t0));
      std::printf("BENCH opt_vs_preset_%s %.3f x\n", algo,
                  Speed(r.best_result) / Speed(preset));
      std::fflush(stdout);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_optimizer: %s\n", e.what());
    return 1;
  }
}
