#include "optimizer/episode/mlp_genes.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "nn_controller/network_genes.h"
#include "nn_controller/nn_observation.h"
#include "optimizer/episode/body_genes.h"
#include "sim_core/physics/physics.h"

namespace mrsim {

MlpShape MlpShapeOf(const ControllerSpec& controller) {
  MlpShape shape;
  shape.joints = controller.joints;
  shape.hidden = controller.hidden;
  shape.imu = controller.imu;
  shape.sensors = std::max(controller.sensors, 0);
  return shape;
}

void ResolveMlpJoints(ControllerSpec* controller, const Scenario& scenario,
                      const std::string& robot) {
  GenomeSpec which;
  which.robot = robot;
  const int index = GenomeRobotIndex(scenario, which);
  // The model as the episodes build it: its hinge count is theirs.
  const int joints = Physics(scenario).joint_count(index);
  if (joints < 1) {
    throw GenomeError(
        fmt::format("{}: the robot has no hinge to drive",
                    ControllerSpec::Kinds().Name(controller->kind)));
  }
  controller->joints = joints;
  if (controller->sensors < 0) {
    // Every value the robot's sensor modules give, as mrsim-nn reads them
    // (nn_observation.h): a force, then the distances, per module.
    NnObservation seen;
    ObservationOf(Physics(scenario).ReadRobotState(index), &seen);
    controller->sensors = static_cast<int>(seen.sensor_values.size());
    if (controller->sensors == 0) {
      throw GenomeError(
          "mlp +sensors: the robot has no force or distance sensor to read");
    }
  }
}

GenomeSpec MlpGenome(const ControllerSpec& controller, const GenomeSpec* user) {
  const MlpShape shape = MlpShapeOf(controller);
  try {
    shape.Validate();
  } catch (const std::invalid_argument& e) {
    throw GenomeError(fmt::format("--controller mlp:{}: {}",
                                  HiddenLayersText(shape.hidden), e.what()));
  }
  GenomeSpec spec;
  const long n = shape.WeightCount();
  spec.genes.reserve(static_cast<size_t>(n) + 1);
  spec.genes.push_back({kPeriodGene, kMinPeriodGene, kMaxPeriodGene,
                        kStartPeriodGene, true, false});
  for (long i = 0; i < n; ++i) {
    spec.genes.push_back({WeightGeneName(i), -kWeightGeneLimit,
                          kWeightGeneLimit, 0, true, false});
  }
  if (user != nullptr) {
    spec.robot = user->robot;
    const auto& body = BodyGeneNames();
    for (const GeneSpec& g : user->genes) {
      if (std::find(body.begin(), body.end(), g.name) == body.end()) {
        throw GenomeError("--genome: gene '" + g.name +
                          "' is not a body gene; with --controller mlp the "
                          "network's weights are the controller's genes");
      }
      if (g.name == "module_count" && g.enabled) {
        throw GenomeError(
            "--genome: module_count changes the joint count, and a "
            "network's size is made for one; fix it (enabled=\"false\") or "
            "optimise the body with --controller gait");
      }
      spec.genes.push_back(g);
    }
  }
  spec.Validate("mlp genome");
  return spec;
}

MlpNetwork MlpNetworkOfGenome(const MlpShape& shape, const GenomeSpec& spec,
                              const Genome& genome) {
  const int period = spec.Find(kPeriodGene);
  const int first = spec.Find(WeightGeneName(0));
  const long n = shape.WeightCount();
  if (period < 0 || first < 0 || first + n > spec.size() ||
      genome.size() != spec.genes.size()) {
    throw GenomeError(fmt::format(
        "the network needs the genes period and w0 to w{} (mlp genome)",
        n - 1));
  }
  std::vector<double> weights(static_cast<size_t>(n));
  for (long i = 0; i < n; ++i) {
    const size_t g = static_cast<size_t>(first + i);
    // Checked in place, not looked up: a network has hundreds of weights
    // and every episode builds one.
    if (spec.genes[g].name != WeightGeneName(i)) {
      throw GenomeError(fmt::format("gene {}: expected {}, got {}", g,
                                    WeightGeneName(i), spec.genes[g].name));
    }
    weights[static_cast<size_t>(i)] = genome[g];
  }
  try {
    return MlpNetwork(shape, std::move(weights), genome[period]);
  } catch (const std::invalid_argument& e) {
    throw GenomeError(std::string("network: ") + e.what());
  }
}

}  // namespace mrsim
