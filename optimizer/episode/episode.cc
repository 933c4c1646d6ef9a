#include "optimizer/episode/episode.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_runner.h"
#include "optimizer/episode/body_genes.h"
#include "optimizer/episode/episode_controller.h"
#include "optimizer/episode/episode_physics_pool.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"

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
  robust.Validate();
  for (double w : {fitness.w_distance, fitness.w_speed, fitness.w_energy,
                   fitness.w_drift, fitness.w_fall}) {
    if (!std::isfinite(w)) {
      throw std::invalid_argument("fitness weights must be finite");
    }
  }
}

void RobustSettings::Validate() const {
  if (episodes < 0 || episodes > kMaxEpisodes) {
    throw std::invalid_argument("robust episodes must be 0.." +
                                std::to_string(kMaxEpisodes) + ", got " +
                                std::to_string(episodes));
  }
  if (mode != "mean" && mode != "worst") {
    throw std::invalid_argument("robust mode: expected mean or worst, got '" +
                                mode + "'");
  }
  gap.Validate();
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

namespace {

// A controller's message as evaluations.csv and the checkpoint keep it: one
// line of at most 1000 bytes.
std::string OneLine(const std::string& message) {
  std::string line = message.substr(0, 1000);
  for (char& ch : line) {
    if (ch == '\n' || ch == '\r' || ch == '\t') ch = ' ';
  }
  return line;
}

// EvalResult::error of a body whose parts overlap at the start.
constexpr char kOverlapReason[] = "overlap at the start: ";

// One episode; in the world of `gap` when given, else the nominal one.
EvalResult RunOneEpisode(const Problem& problem, const Genome& genome,
                         const std::function<bool()>& stop,
                         EpisodePhysicsPool* pool, const RealityGap* gap) {
  const EpisodeSettings& e = problem.episode;
  EvalResult result;
  try {
    Scenario scenario =
        ApplyBodyGenes(problem.scenario, problem.genome, genome);
    if (gap) scenario = PerturbScenario(scenario, *gap);
    const int robot = GenomeRobotIndex(scenario, problem.genome);
    PhysicsLease lease(pool, scenario);
    Physics& physics = *lease;
    // On the model already built (its start pose), not a second compile.
    if (GenomeBuildsTheBody(problem.genome) && !e.allow_overlap) {
      const std::vector<PartOverlap> overlaps =
          FindOverlapsInModel(scenario, physics.model());
      if (!overlaps.empty()) {
        result.failed = true;
        result.fitness = kFailedFitness;
        // The deepest pair, without its depth: individuals grown into the
        // same part give the same reason, which mrsim-opt counts.
        result.error = OneLine(kOverlapReason + overlaps[0].first + " / " +
                               overlaps[0].second);
        return result;
      }
    }
    // Always set: a pooled simulation may come from a perturbed episode.
    physics.SetRealityGap(gap ? *gap : RealityGap{});
    const std::vector<Axis> axes = JointAxes(physics, robot);
    // Another controller kind than the gait (episode_controller.h).
    std::unique_ptr<EpisodeController> other =
        MakeEpisodeController(problem, genome, axes);
    std::optional<GaitController> gait;
    if (!other) {
      gait.emplace(axes);
      gait->SetGait(GaitOfGenome(problem, genome));
    }

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
    ControllerRunResult run;
    if (other) {
      run = RunController(physics, robot, *other, e.duration, e.control_period,
                          observer);
    } else {
      const GaitRunResult g = RunGait(physics, robot, *gait, e.duration,
                                      e.control_period, observer);
      run.com_start = g.com_start;
      run.com_end = g.com_end;
      run.energy = g.energy;
    }
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
  } catch (const ControllerError& err) {
    // The script's own error, kept for evaluations.csv: the same on every
    // worker (the sandbox counts instructions, not time).
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
    result.error = OneLine(err.what());
  } catch (const PhysicsError&) {
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
    result.error = "the simulation became unstable";
  } catch (const std::invalid_argument& err) {
    // Gait values the controller refuses (e.g. T below its minimum).
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
    result.error = OneLine(std::string("gait values refused: ") + err.what());
  } catch (const ScenarioError& err) {
    // A body the validator refuses (the genome's limits allowed it): a
    // failed individual, the same in one process and on every worker.
    result = EvalResult{};
    result.failed = true;
    result.fitness = kFailedFitness;
    result.error = OneLine(std::string("body refused: ") + err.what());
  }
  return result;
}

}  // namespace

EvalResult RunEpisode(const Problem& problem, const Genome& genome,
                      const std::function<bool()>& stop,
                      EpisodePhysicsPool* pool) {
  if (genome.size() != problem.genome.genes.size()) {
    throw GenomeError("genome has the wrong number of values");
  }
  const RobustSettings& robust = problem.episode.robust;
  if (robust.episodes <= 0) {
    return RunOneEpisode(problem, genome, stop, pool, nullptr);
  }
  // K perturbed worlds: the measures are their means, the fitness their
  // mean or worst; one failed world fails the genome (a robot that breaks
  // in one of K plausible worlds is not robust).
  EvalResult sum;
  double worst = 0;
  for (int k = 0; k < robust.episodes; ++k) {
    const RealityGap gap = robust.gap.ForEpisode(k);
    const EvalResult r = RunOneEpisode(problem, genome, stop, pool, &gap);
    if (r.failed) return r;
    sum.fitness += r.fitness;
    sum.distance += r.distance;
    sum.speed += r.speed;
    sum.energy += r.energy;
    sum.drift += r.drift;
    sum.fell += r.fell;
    worst = k == 0 ? r.fitness : std::min(worst, r.fitness);
  }
  const double n = robust.episodes;
  EvalResult mean;
  mean.fitness = robust.mode == "worst" ? worst : sum.fitness / n;
  mean.distance = sum.distance / n;
  mean.speed = sum.speed / n;
  mean.energy = sum.energy / n;
  mean.drift = sum.drift / n;
  mean.fell = sum.fell / n;
  return mean;
}

}  // namespace mrsim
