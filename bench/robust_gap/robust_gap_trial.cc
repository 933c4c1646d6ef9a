#include "bench/robust_gap/robust_gap_trial.h"

#include <vector>

#include "gait_controller/gait_presets.h"
#include "optimizer/search/local_evaluator.h"
#include "optimizer/search/optimization_run.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/episode/task.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {

namespace {

// Through the codec, as a worker receives it: assets embedded, validated.
Problem AsSent(const Problem& p) {
  return DecodeProblem(EncodeProblem(p), "bench");
}

RunResult Optimise(const RobustGapTask& task, int robust, uint64_t seed,
                   const RobustGapBudget& budget) {
  Problem problem = task.problem;
  problem.episode.robust.episodes = robust;
  problem.episode.robust.gap.seed = seed;
  AlgorithmSettings a;
  a.algorithm = ParseAlgorithm("cmaes");
  a.population = budget.population;
  a.seed = seed;
  a.include_start = task.include_start;
  OptimizationRunOptions options;
  options.generations = budget.generations;
  LocalEvaluator evaluator(
      [&](const Genome& g) { return RunEpisode(problem, g); }, budget.threads);
  return RunOptimization(problem.genome, a, evaluator, options);
}

KeptShare Replay(const RobustGapTask& task, const RunResult& trained,
                 const RobustGapBudget& budget) {
  const Genome& genes = trained.best;
  KeptShare k;
  k.genes = genes;
  k.reported = trained.best_result.fitness;
  k.nominal = RunEpisode(task.problem, genes).fitness;
  RobustSettings worlds;
  worlds.episodes = budget.replay_worlds;
  worlds.gap.seed = budget.replay_seed;
  double sum = 0;
  for (int i = 0; i < budget.replay_worlds; ++i) {
    Problem one = task.problem;
    one.episode.robust.episodes = 1;
    one.episode.robust.gap = worlds.gap.ForEpisode(i);
    const EvalResult r = RunEpisode(one, genes);
    // A world the gait fails in is no headway, not the failure sentinel.
    sum += r.failed ? 0.0 : r.fitness;
  }
  k.perturbed = sum / budget.replay_worlds;
  k.share = k.reported > 0 ? k.perturbed / k.reported : 0.0;
  return k;
}

}  // namespace

std::vector<RobustGapTask> RobustGapTasks(const std::string& source_dir,
                                          double episode_seconds) {
  std::vector<RobustGapTask> tasks;
  {
    RobustGapTask t;
    t.name = "snake11-tumble";
    t.why =
        "snake11, forward genes, no start genome: the nominal best "
        "tumbles (docs/physics.md)";
    t.problem.scenario =
        ReadScenarioFile(source_dir + "/scenarios/snake11.xml");
    t.problem.genome =
        ReadGenomeFile(source_dir + "/scenarios/forward_gait.genome.xml");
    t.problem.episode.duration = episode_seconds;
    t.problem.episode.base_gait = *FindGaitPreset("forward");
    t.problem = AsSent(t.problem);
    t.include_start = false;
    tasks.push_back(t);
  }
  {
    const Task flat = MakeTask("flat");
    RobustGapTask t;
    t.name = "task-flat-sine";
    t.why = "the task suite's flat task, the seven sine genes";
    t.problem = AsSent(
        TaskProblem(flat, flat.gait, BuiltInGenome("sine"), episode_seconds));
    t.include_start = true;
    tasks.push_back(t);
  }
  return tasks;
}

RobustGapResult RunRobustGapTrial(const RobustGapTask& task, uint64_t seed,
                                  const RobustGapBudget& budget) {
  RobustGapResult r;
  r.nominal_gait = Replay(task, Optimise(task, 0, seed, budget), budget);
  r.robust_gait = Replay(
      task, Optimise(task, budget.robust_episodes, seed, budget), budget);
  r.ratio = r.nominal_gait.share > 0
                ? r.robust_gait.share / r.nominal_gait.share
                : 0.0;
  return r;
}

}  // namespace mrsim
