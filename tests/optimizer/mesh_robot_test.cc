// Robots built from mesh frames can be optimised: the payload carries the
// mesh files, and body genes that need no rebuild keep the robot's parts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gait_controller/gait_presets.h"
#include "optimizer/episode/body_genes.h"
#include "optimizer/episode/episode.h"
#include "optimizer/episode/problem_codec.h"
#include "sim_core/scenario/chain_builder.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

// A 4-module chain whose frames are a cube mesh (OBJ), with a sensor
// module placed by hand beside module 1.
Problem MeshProblem(const std::string& dir) {
  std::ofstream(dir + "/cube.obj")
      << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
         "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
         "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  Problem p;
  p.scenario.base_dir = dir;
  p.scenario.contact_frictions.push_back({"plastic", "ground", 0, 0.6, 2e9});
  ChainOptions options;
  options.modules = 4;
  options.sensor_after = {1};
  Robot robot = MakeChain(options);
  for (Module& m : robot.modules) {
    for (Frame& f : m.frames) {
      f.shape = "cube.obj";
      f.scale = Eigen::Vector3d(0.025, 0.025, 0.025);  // a 5 cm cube
    }
  }
  robot.sensor_modules[0].position.y() += 0.01;  // hand-placed
  p.scenario.robots.push_back(robot);
  p.genome = ReadGenomeString(R"(<genome>
  <gene name="A_pitch" lower="0" upper="1.5" start="1"/>
  <gene name="module_scale" lower="0.5" upper="2" start="1"/>
</genome>)",
                              "mesh genome");
  p.episode.duration = 2.0;
  p.episode.base_gait = *FindGaitPreset("forward");
  return p;
}

TEST(OptimizerMeshRobot, PayloadCarriesTheMeshFiles) {
  const std::string dir = testing::TempDir("opt_mesh_payload");
  const Problem problem = MeshProblem(dir);
  const std::string payload = EncodeProblem(problem);
  EXPECT_EQ(payload.find(dir), std::string::npos) << "names a file";
  // A worker has no files: the mesh is gone, the payload still runs.
  std::filesystem::remove(dir + "/cube.obj");
  const Problem decoded = DecodeProblem(payload, "payload");
  const EvalResult local = RunEpisode(decoded, decoded.genome.StartGenome());
  EXPECT_FALSE(local.failed);
  EXPECT_GT(local.distance, 0.0);
  // The same bytes give the same result.
  const Problem again = DecodeProblem(payload, "payload");
  EXPECT_EQ(RunEpisode(again, again.genome.StartGenome()).fitness,
            local.fitness);
}

TEST(OptimizerMeshRobot, ScaleGeneKeepsAHandBuiltRobotsParts) {
  const std::string dir = testing::TempDir("opt_mesh_scale");
  const Problem problem = MeshProblem(dir);
  const Robot& before = problem.scenario.robots[0];
  const Scenario s =
      ApplyBodyGenes(problem.scenario, problem.genome, Genome{1.0, 2.0});
  const Robot& after = s.robots[0];
  ASSERT_EQ(after.modules.size(), before.modules.size());
  for (size_t i = 0; i < after.modules.size(); ++i) {
    for (int f = 0; f < 2; ++f) {
      EXPECT_EQ(after.modules[i].frames[f].shape, "cube.obj");
      EXPECT_EQ(after.modules[i].frames[f].scale,
                2.0 * before.modules[i].frames[f].scale);
    }
  }
  // Scaled about the ground under module 0's hinge: still on the ground,
  // the hand-placed sensor module keeps its (scaled) offset.
  EXPECT_DOUBLE_EQ(after.modules[0].position.z(),
                   2.0 * before.modules[0].position.z());
  EXPECT_DOUBLE_EQ(after.modules[0].position.x(),
                   before.modules[0].position.x());
  EXPECT_DOUBLE_EQ(after.sensor_modules[0].position.y(), 0.02);
  Problem scaled = problem;
  EXPECT_FALSE(RunEpisode(scaled, Genome{1.0, 2.0}).failed);
}

}  // namespace
}  // namespace mrsim
