#include "studio/live/best_replay.h"

#include <filesystem>

#include "gait_controller/gait_file.h"
#include "optimizer/episode/body_genes.h"
#include "optimizer/episode/episode.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim::studio {

BestReplay MakeBestReplay(const OptimiseOptions& options,
                          const GenerationRow& row) {
  Problem problem;
  problem.scenario = ReadScenarioFile(options.scenario_path);
  problem.genome = options.genome;
  problem.episode.base_gait = ResolveGait(options.base_gait);
  Genome genome;
  for (int i = 0; i < problem.genome.size(); ++i) {
    const GeneSpec& gene = problem.genome.genes[i];
    const auto it = row.genes.find(gene.name);
    genome.push_back(it == row.genes.end()
                         ? gene.start
                         : problem.genome.Legal(i, it->second));
  }
  BestReplay replay;
  replay.generation = row.generation;
  replay.fitness = row.best;
  replay.scenario = ApplyBodyGenes(problem.scenario, problem.genome, genome);
  replay.gait = GaitOfGenome(problem, genome);
  replay.body = !(replay.scenario == problem.scenario);
  replay.robot =
      replay.scenario.robots[GenomeRobotIndex(replay.scenario, problem.genome)]
          .name;
  return replay;
}

RunOptions WriteBestReplay(const BestReplay& replay, const std::string& dir,
                           RunOptions run) {
  // Absolute: the processes need not run where the studio does.
  const std::string abs = std::filesystem::absolute(dir).string();
  std::filesystem::create_directories(abs);
  run.scenario_path = abs + "/best_scenario.xml";
  const std::string gait_path = abs + "/best_gait.xml";
  WriteScenarioFile(replay.scenario, run.scenario_path);
  WriteGaitFile(replay.gait, gait_path);
  run.robots.clear();
  for (const Robot& robot : replay.scenario.robots) {
    run.robots.push_back(robot.name);
  }
  run.gait = gait_path;
  return run;
}

}  // namespace mrsim::studio
