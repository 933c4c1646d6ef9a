// --controller mlp:H in the optimiser: the flag, the genes (period and one
// weight per connection, symmetric limits, sized by the robot's joints),
// body genes alongside, the problem payload a farm worker receives, and
// episodes that repeat bit for bit.
#include "optimizer/episode/mlp_genes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "nn_controller/network_genes.h"
#include "optimizer/episode/controller_genes.h"
#include "optimizer/episode/episode.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/episode/task.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

Problem FlatMlpProblem(const std::string& flag) {
  const Task task = MakeTask("flat");
  Problem p = TaskProblem(task, task.gait, GenomeSpec{}, 1.0);
  p.controller = ParseControllerFlag(flag);
  ResolveMlpJoints(&p.controller, p.scenario, "");
  p.genome = ControllerGenome(p.controller, nullptr);
  return p;
}

TEST(MlpController, FlagGivesTheHiddenLayersAndRefusesNonsense) {
  const ControllerSpec spec = ParseControllerFlag("mlp:16,4");
  EXPECT_EQ(spec.kind, ControllerSpec::Kind::kMlp);
  EXPECT_EQ(spec.hidden, (std::vector<int>{16, 4}));
  EXPECT_EQ(spec.name, "16,4");  // resume names controller=mlp:16,4
  for (const char* bad : {"mlp:", "mlp:0", "mlp:x", "mlp:8,", "mlp"}) {
    try {
      ParseControllerFlag(bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--controller"), std::string::npos)
          << e.what();
    }
  }
}

TEST(MlpController, GenesArePeriodAndEveryWeightWithinSymmetricLimits) {
  const Problem p = FlatMlpProblem("mlp:8");
  ASSERT_GT(p.controller.joints, 0);
  const MlpShape shape = MlpShapeOf(p.controller);
  ASSERT_EQ(p.genome.size(), shape.WeightCount() + 1);
  EXPECT_EQ(p.genome.genes[0].name, "period");
  for (long i = 0; i < shape.WeightCount(); ++i) {
    const GeneSpec& g = p.genome.genes[static_cast<size_t>(i) + 1];
    ASSERT_EQ(g.name, WeightGeneName(i));
    EXPECT_EQ(g.lower, -g.upper);
  }
  // Two hidden layers: more genes, the same layout.
  EXPECT_EQ(FlatMlpProblem("mlp:8,8").genome.size(),
            MlpShapeOf(FlatMlpProblem("mlp:8,8").controller).WeightCount() + 1);
}

TEST(MlpController, BodyGenesCombineButModuleCountIsRefused) {
  ControllerSpec spec = ParseControllerFlag("mlp:4");
  spec.joints = 6;
  GenomeSpec user;
  user.genes = {{"joint_kp", 1, 20, 5, true, false}};
  const GenomeSpec g = MlpGenome(spec, &user);
  EXPECT_EQ(g.genes.back().name, "joint_kp");
  user.genes = {{"module_count", 4, 12, 8, true, true}};
  EXPECT_THROW(MlpGenome(spec, &user), GenomeError);
  user.genes = {{"A_pitch", 0, 1, 0.5, true, false}};
  EXPECT_THROW(MlpGenome(spec, &user), GenomeError);
}

TEST(MlpController, PayloadKeepsTheShapeAndEpisodesRepeatBitForBit) {
  const Problem p = FlatMlpProblem("mlp:6");
  const Problem back = DecodeProblem(EncodeProblem(p), "test");
  EXPECT_EQ(back.controller.kind, ControllerSpec::Kind::kMlp);
  EXPECT_EQ(back.controller.hidden, p.controller.hidden);
  EXPECT_EQ(back.controller.joints, p.controller.joints);
  Genome genome = p.genome.StartGenome();
  for (size_t i = 1; i < genome.size(); ++i) genome[i] = std::sin(1.3 * i);
  const EvalResult a = RunEpisode(p, genome);
  const EvalResult b = RunEpisode(back, genome);
  EXPECT_FALSE(a.failed);
  EXPECT_EQ(a.fitness, b.fitness);
  EXPECT_EQ(a.energy, b.energy);
  EXPECT_NE(a.distance, 0);
}

TEST(MlpController, ImuAndSensorInputsWidenTheNetworkAndTravelInThePayload) {
  // The case study: six sensor modules with force plates, a distance
  // sensor at the front.
  const Task task = MakeTask("flat");
  Problem p = TaskProblem(task, task.gait, GenomeSpec{}, 0.5);
  p.scenario =
      ReadScenarioFile(testing::SourcePath("scenarios/case_study.xml"));
  auto genes_of = [&](const std::string& flag) {
    p.controller = ParseControllerFlag(flag);
    ResolveMlpJoints(&p.controller, p.scenario, "");
    p.genome = ControllerGenome(p.controller, nullptr);
    return p.genome.size();
  };
  const int plain = genes_of("mlp:4");
  const int with_imu = genes_of("mlp:4+imu");
  EXPECT_EQ(with_imu - plain, MlpShape::kImuInputs * 4);  // 7 inputs x 4
  const int with_all = genes_of("mlp:4+imu+sensors");
  EXPECT_EQ(p.controller.name, "4+imu+sensors");
  EXPECT_GE(p.controller.sensors, 7) << "six forces and a distance at least";
  EXPECT_EQ(with_all - with_imu, p.controller.sensors * 4);

  const Problem back = DecodeProblem(EncodeProblem(p), "test");
  EXPECT_TRUE(back.controller.imu);
  EXPECT_EQ(back.controller.sensors, p.controller.sensors);
  Genome genome = p.genome.StartGenome();
  for (size_t i = 1; i < genome.size(); ++i) genome[i] = std::sin(0.7 * i);
  const EvalResult a = RunEpisode(p, genome);
  EXPECT_FALSE(a.failed);
  EXPECT_EQ(a.fitness, RunEpisode(back, genome).fitness);

  for (const char* bad : {"mlp:4+gps", "mlp:4+imu+imu", "mlp:4+"}) {
    EXPECT_THROW(ParseControllerFlag(bad), std::invalid_argument) << bad;
  }
  // The tasks' snake carries no sensor: +sensors has nothing to read.
  EXPECT_THROW(FlatMlpProblem("mlp:4+sensors"), GenomeError);
}

TEST(MlpController, APayloadWithoutItsJointsIsRefused) {
  try {
    DecodeControllerSpec("kind=mlp\nname=mlp:8\nhidden=8\n\n", "farm");
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("farm: controller section"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(DecodeControllerSpec(
                   "kind=mlp\nname=mlp:8\nhidden=8\njoints=99999\n\n", "farm"),
               std::invalid_argument);
}

}  // namespace
}  // namespace mrsim
