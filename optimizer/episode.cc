#include "optimizer/episode.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_runner.h"
#include "optimizer/body_genes.h"
#include "optimizer/episode_physics_pool.h"
#include "sim_core/physics.h"
#include "sim_core/scenario_xml.h"

namespace mrsim {

const EnumTable<DistanceMode>& DistanceModes() {
  static const EnumTable<DistanceMode> kModes(
      "fitness distance mode", {{DistanceMode::kForward, "forward"},
                                {DistanceMode::kNet, "net"},
                                {DistanceMode::kUp, "up"}});
  return kModes;
}

void EpisodeSettings::Validate() const {
  if (!(duration > 0) || !std::isfinite(duration)) {
    throw std::invalid_argument("episode duration must be > 0 s");
  }
  if (!(control_period > 0)) {
    throw std::invalid_argument("control period must be > 0 s");
  }
  // A value cast from a number, not one of the table's.
  DistanceModes().Parse(ToString(fitness.distance_mode));
  for (double w : {fitness.w_distance, fitness.w_speed, fitness.w_energy,
                   fitness.w_drift, fitness.w_fall}) {
    if (!std::isfinite(w)) {
      throw std::invalid_argument("fitness weights must be finite");
    }
  }
}

Gait GaitOfGenome(const Problem& problem, const Genome& genome) {
  Gait gait = problem.episode.base_gait;
  std::vector<double> values = gait.parameters.ToVector();
  const auto& names = GaitGeneNames();
  for (size_t k = 0; k < names.size(); ++k) {
    const int i = problem.genome.Find(names[k]);
    if (i >= 0) values[k] = genome[i];
  }
  gait.parameters = gait.parameters.WithVector(values);
  const auto& cpg_names = CpgGeneNames();
  for (size_t k = 0; k < cpg_names.size(); ++k) {
    const int i = problem.genome.Find(cpg_names[k]);
    if (i < 0) continue;
    // Any CPG gene makes it a CPG gait.
    if (!gait.cpg) gait.cpg = CpgParameters{};
    double* fields[] = {&gait.cpg->coupling, &gait.cpg->convergence,
                        &gait.cpg->feedback_gain};
    *fields[k] = genome[i];
  }
  gait.name = "optimised";
  return gait;
}

void PrepareEpisode(const Problem& problem, EpisodePhysicsPool* pool) {
  try {
    PhysicsLease lease(pool, ApplyBodyGenes(problem.scenario, problem.genome,
                                            problem.genome.StartGenome()));
  } catch (const std::exception&) {
    // Its episodes report it.
  }
}

EvalResult RunEpisode(const Problem& problem, const Genome& genome,
                      const std::function<bool()>& stop,
                      EpisodePhysicsPool* pool) {
  if (genome.size() != problem.genome.genes.size()) {
    throw GenomeError("genome has the wrong number of values");
  }
  const EpisodeSettings& e = problem.episode;
  EvalResult result;
  try {
    const Scenario scenario =
        ApplyBodyGenes(problem.scenario, problem.genome, genome);
    const int robot = GenomeRobotIndex(scenario, problem.genome);
    PhysicsLease lease(pool, scenario);
    Physics& physics = *lease;
    GaitController controller(JointAxes(physics, robot));
    controller.SetGait(GaitOfGenome(problem, genome));

    // Upside down: the mean of the module frames' z axes points down.
    int samples = 0, upside_down = 0;
    int period = 0;
    auto observer = [&](const Physics& p, const std::vector<double>&) {
      if (period++ % 10 != 0) return;
      if (stop && stop()) throw EvaluationInterrupted("episode interrupted");
      const RobotState state = p.ReadRobotState(robot);
      Eigen::Vector3d up = Eigen::Vector3d::Zero();
      for (const Pose& m : state.modules) {
        up += m.orientation * Eigen::Vector3d::UnitZ();
      }
      ++samples;
      upside_down += up.z() < 0 ? 1 : 0;
    };
    const GaitRunResult run = RunGait(physics, robot, controller, e.duration,
                                      e.control_period, observer);
    const Eigen::Vector3d d = run.com_end - run.com_start;
    result.distance = e.fitness.distance_mode == DistanceMode::kNet
                          ? std::hypot(d.x(), d.y())
                      : e.fitness.distance_mode == DistanceMode::kUp ? d.z()
                                                                     : d.x();
    result.speed = result.distance / e.duration;
    result.energy = run.energy;
    result.drift = std::abs(d.y());
    result.fell = samples > 0 ? static_cast<double>(upside_down) / samples : 0;
    const FitnessSettings& w = e.fitness;
    result.fitness = w.w_distance * result.distance + w.w_speed * result.speed -
                     w.w_energy * result.energy - w.w_drift * result.drift -
                     w.w_fall * result.fell;
    if (!std::isfinite(result.fitness)) throw PhysicsError("non-finite");
  } catch (const PhysicsError&) {
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
  } catch (const std::invalid_argument&) {
    // Gait values the controller refuses (e.g. T below its minimum).
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
  } catch (const ScenarioError&) {
    // A body the validator refuses (the genome's limits allowed it): a
    // failed individual, the same in one process and on every worker.
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
  }
  return result;
}

}  // namespace mrsim
