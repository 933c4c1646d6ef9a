#include "bench/optimizer/lua_episode_rate_ratio.h"

#include <time.h>

#include <cstdio>
#include <string>

#include "bench/common/paired_ratio.h"
#include "optimizer/episode/controller_genes.h"
#include "optimizer/episode/episode.h"
#include "optimizer/episode/episode_physics_pool.h"
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

int BenchLuaEpisodeRateRatio() {
  const Task task = MakeTask("flat");
  const double seconds = 3.0;
  const Problem gait =
      Decoded(TaskProblem(task, task.gait, ForwardGaitGenome(), seconds));
  Problem lua_problem = TaskProblem(task, task.gait, GenomeSpec{}, seconds);
  lua_problem.controller =
      ParseControllerFlag(std::string("lua:") + MRSIM_SOURCE_DIR +
                          "/examples/optimise/serpenoid_params.lua");
  lua_problem.genome = ControllerGenome(lua_problem.controller, nullptr);
  const Problem lua = Decoded(lua_problem);
  // Both reuse their simulation between episodes, as a worker does.
  EpisodePhysicsPool pool;
  bool failed = false;
  auto rate = [&](const Problem& problem) {
    const Genome genome = problem.genome.StartGenome();
    const int episodes = 10;
    const double t0 = ThreadCpu();
    for (int i = 0; i < episodes; ++i) {
      failed |= RunEpisode(problem, genome, {}, &pool).failed;
    }
    return episodes / (ThreadCpu() - t0);  // episodes per CPU second
  };
  rate(gait);  // warm: build the simulation once
  const PairedRatio r =
      RunPaired([&] { return rate(lua); }, [&] { return rate(gait); }, 21);
  std::printf(
      "# lua episode: %.4f CPU-s, gait episode %.4f CPU-s (medians, "
      "%g s of sim time)\n",
      1.0 / r.median_a, 1.0 / r.median_b, seconds);
  PrintBench("lua_episode_rate_ratio", r, "x", "episodes/CPU-s, lua / gait");
  if (failed) std::fprintf(stderr, "bench: an episode failed\n");
  return failed ? 1 : 0;
}

}  // namespace mrsim
