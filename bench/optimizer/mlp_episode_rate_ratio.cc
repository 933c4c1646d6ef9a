#include "bench/optimizer/mlp_episode_rate_ratio.h"

#include <time.h>

#include <cmath>
#include <cstdio>

#include "bench/common/paired_ratio.h"
#include "optimizer/episode/controller_genes.h"
#include "optimizer/episode/episode.h"
#include "optimizer/episode/episode_physics_pool.h"
#include "optimizer/episode/mlp_genes.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/episode/task.h"

namespace mrsim {
namespace {

double ThreadCpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

// As mrsim-opt evaluates it: the payload's round trip.
Problem Decoded(const Problem& p) {
  return DecodeProblem(EncodeProblem(p), "bench");
}

}  // namespace

int BenchMlpEpisodeRateRatio() {
  const Task task = MakeTask("flat");
  const double seconds = 3.0;
  const Problem gait =
      Decoded(TaskProblem(task, task.gait, ForwardGaitGenome(), seconds));
  Problem mlp_problem = TaskProblem(task, task.gait, GenomeSpec{}, seconds);
  mlp_problem.controller = ParseControllerFlag("mlp:16");
  ResolveMlpJoints(&mlp_problem.controller, mlp_problem.scenario, "");
  mlp_problem.genome = ControllerGenome(mlp_problem.controller, nullptr);
  const Problem mlp = Decoded(mlp_problem);
  // A network that moves the robot (all-zero weights would hold it
  // still, which the physics simulates faster than a gait).
  Genome mlp_genome = mlp.genome.StartGenome();
  for (size_t i = 1; i < mlp_genome.size(); ++i) {
    mlp_genome[i] = std::sin(1.7 * static_cast<double>(i));
  }
  // Both reuse their simulation between episodes, as a worker does.
  EpisodePhysicsPool pool;
  bool failed = false;
  auto rate = [&](const Problem& problem, const Genome& genome) {
    const int episodes = 3;
    const double t0 = ThreadCpu();
    for (int i = 0; i < episodes; ++i) {
      failed |= RunEpisode(problem, genome, {}, &pool).failed;
    }
    return episodes / (ThreadCpu() - t0);  // episodes per CPU second
  };
  const Genome gait_genome = gait.genome.StartGenome();
  rate(gait, gait_genome);  // warm: build the simulation once
  const PairedRatio r = RunPaired([&] { return rate(mlp, mlp_genome); },
                                  [&] { return rate(gait, gait_genome); }, 15);
  std::printf(
      "# mlp:16 episode (%zu genes): %.4f CPU-s, gait episode %.4f CPU-s "
      "(medians, %g s of sim time)\n",
      mlp_genome.size(), 1.0 / r.median_a, 1.0 / r.median_b, seconds);
  PrintBench("mlp_episode_rate_ratio", r, "x", "episodes/CPU-s, mlp / gait");
  if (failed) std::fprintf(stderr, "bench: an episode failed\n");
  return failed ? 1 : 0;
}

}  // namespace mrsim
