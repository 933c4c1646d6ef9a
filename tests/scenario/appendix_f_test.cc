// The original MRSim's own example, its thesis's Appendix F (assembled
// from the printed fragments in tests/scenario/data/), loads the way a
// user would load it: converted from Unity's frame, validated, exported
// as MJCF that MuJoCo compiles, and run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario_tool/scenario_command.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;
using testing::SourcePath;
using testing::TempDir;

// Runs `mrsim-scenario ARGS...` in process; its info stream (stderr).
std::string RunScenarioTool(std::vector<std::string> args) {
  args.insert(args.begin(), "mrsim-scenario");
  CLI::App app;
  ScenarioCommand command;
  AddScenarioFlags(app, command);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  std::ostringstream out, info;
  RunScenarioCommand(command, out, info);
  return info.str();
}

TEST(AppendixF, TheThesisExampleConvertsValidatesAndRuns) {
  const std::string dir = TempDir("appendix_f");
  const std::string original =
      SourcePath("tests/scenario/data/appendix_f_case_study.xml");
  ASSERT_TRUE(IsOriginalMrsimFile(original));
  const std::string native = dir + "/appendix_f.xml";
  std::string told;
  ASSERT_NO_THROW(told = RunScenarioTool(
                      {"convert", "--from", "unity-y-up", original, native}));

  // A native file now, read (and validated) like any other.
  const Scenario s = ReadScenarioFile(native);
  ASSERT_EQ(s.robots.size(), 1u);
  ASSERT_EQ(s.robots[0].modules.size(), 1u);
  ASSERT_EQ(s.robots[0].sensor_modules.size(), 1u);
  ASSERT_EQ(s.scene_objects.size(), 1u);
  EXPECT_NO_THROW(ValidateScenario(s));

  // The front sensor looks along the chain at the ball: Unity's forward
  // (0, 0, 1) is +y here, the face the ray leaves through is face 1, and
  // the ball (four units ahead) is straight along it.
  const SensorModule& sm = s.robots[0].sensor_modules[0];
  ASSERT_EQ(sm.distance_sensors.size(), 1u);
  const DistanceSensor& ray = sm.distance_sensors[0];
  EXPECT_TRUE(ray.ray_direction.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(ray.sensor_position, 1);
  const Eigen::Vector3d world_ray =
      sm.quat_rotation.normalized() * ray.ray_direction.normalized();
  const Eigen::Vector3d to_ball = s.scene_objects[0].position - sm.position;
  EXPECT_NEAR(world_ray.dot(to_ball.normalized()), 1.0, 1e-6);
  EXPECT_NEAR(to_ball.norm(), 4.0, 1e-6);

  // Its frames, unit boxes scaled by the printed 10, enclose the 0.3-unit
  // sensor module in front of them, so the ray starts inside module 0: a
  // warning (told by convert too), never a refusal.
  const std::vector<ScenarioWarning> warnings = ScenarioWarnings(s);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0].message, HasSubstr("the ray of face 1 (left)"));
  EXPECT_THAT(told, HasSubstr("warning: the ray of face 1 (left)"));

  // The MJCF export compiles in MuJoCo.
  const std::string mjcf = dir + "/appendix_f.mjcf.xml";
  ASSERT_NO_THROW(RunScenarioTool({"export-mjcf", native, "-o", mjcf}));
  char error[1000] = "";
  mjModel* model = mj_loadXML(mjcf.c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(model, nullptr) << error;
  if (model != nullptr) mj_deleteModel(model);

  // And it runs: a few hundred steps, every pose finite.
  Physics physics(s);
  physics.Step(300);
  const RobotState state = physics.ReadRobotState(0);
  EXPECT_GT(state.time, 0);
  for (const Pose& frame : state.frames) {
    EXPECT_TRUE(frame.position.allFinite());
  }
  ASSERT_EQ(state.sensor_modules.size(), 1u);
  ASSERT_EQ(state.sensor_modules[0].distances.size(), 1u);
  EXPECT_TRUE(std::isfinite(state.sensor_modules[0].distances[0]));
}

}  // namespace
}  // namespace mrsim
