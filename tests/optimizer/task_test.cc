// The task suite: every task builds, is the same each time, scores with
// its own fitness; mrsim-opt takes --task and --genes.
#include "optimizer/episode/task.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>

#include "gait_controller/gait_controller.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "optimizer/search/genome.h"
#include "optimizer/process/opt_command.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

TEST(TaskSuite, EveryTaskBuildsAValidWorldWithTheTaskRobot) {
  const std::vector<std::string> expected = {
      "flat", "slope", "stairs", "pegs", "pipe", "pole", "rubble", "water"};
  EXPECT_EQ(TaskNames(), expected);
  for (const std::string& name : TaskNames()) {
    SCOPED_TRACE(name);
    const Task t = MakeTask(name);
    EXPECT_EQ(t.name, name);
    EXPECT_FALSE(t.description.empty());
    ASSERT_EQ(t.scenario.robots.size(), 1u);
    EXPECT_EQ(t.scenario.robots[0].name, kTaskRobot);
    EXPECT_EQ(static_cast<int>(t.scenario.robots[0].modules.size()),
              kTaskModules);
    ValidateScenario(t.scenario);
    const Physics physics(t.scenario);
    EXPECT_EQ(physics.joint_count(0), kTaskModules);
    // Same name, same task (the rubble is seeded), through the file too.
    EXPECT_EQ(WriteScenarioString(MakeTask(name).scenario),
              WriteScenarioString(t.scenario));
  }
}

TEST(TaskSuite, AnUnknownTaskNamesTheKnownOnes) {
  try {
    MakeTask("moon");
    FAIL() << "accepted an unknown task";
  } catch (const TaskError& e) {
    EXPECT_NE(std::string(e.what()).find("moon"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("rubble"), std::string::npos);
  }
}

TEST(TaskSuite, ThePoleScoresHeightAndTheOthersDistanceAlongX) {
  for (const std::string& name : TaskNames()) {
    EXPECT_EQ(MakeTask(name).distance_mode, name == "pole" ? "up" : "forward")
        << name;
  }
  // The forward gait on flat ground moves the robot ahead (+x).
  const EvalResult r =
      EvaluateTask(MakeTask("flat"), *FindGaitPreset("forward"), 8.0);
  EXPECT_FALSE(r.failed);
  EXPECT_GT(r.distance, 0.05);
}

TEST(TaskSuite, TheWrappedPoleRobotStartsRoundThePole) {
  const Task t = MakeTask("pole");
  const Physics physics(t.scenario);
  const RobotState s = physics.ReadRobotState(0);
  const double pole_radius = t.scenario.scene_objects[0].size.x() / 2;
  for (const Pose& m : s.modules) {
    const double r = m.position.head<2>().norm();
    EXPECT_GT(r, pole_radius);
    EXPECT_LT(r, pole_radius + 0.1);
  }
}

// The pole task's own gait (helical rolling round the pole, docs/gait.md)
// with real physics: it climbs, and with its servos limp (no torque: the
// same world and state, every hinge's stall torque next to nothing) the
// squeeze is gone and it slides back down.
TEST(TaskSuite, HelicalRollingClimbsThePoleAndSlidesBackWhenTheServosGoLimp) {
  const Task t = MakeTask("pole");
  Physics physics(t.scenario);
  GaitController controller(JointAxes(physics, 0));
  controller.SetGait(t.gait);
  const double z0 = physics.CenterOfMass(0).z();
  RunGait(physics, 0, controller, 30.0, 0.01);
  const double climbed = physics.CenterOfMass(0).z() - z0;
  EXPECT_GE(climbed, 0.3) << "m in 30 s";

  Scenario limp = t.scenario;
  for (Module& m : limp.robots[0].modules) m.joint.max_torque = 1e-6;
  Physics limp_physics(limp);
  limp_physics.LoadState(physics.SaveState());
  const double t0 = limp_physics.time();
  while (limp_physics.time() - t0 < 1.0) limp_physics.Step();
  const double after = limp_physics.CenterOfMass(0).z() - z0;
  EXPECT_LT(after, climbed - 0.1) << "m after 1 s limp, from " << climbed;
}

// What mrsim-opt --genes cpg evaluates first on a task: its start genome.
EvalResult CpgStartGenomeOn(const std::string& task) {
  const Task t = MakeTask(task);
  const Problem p = TaskProblem(t, t.gait, BuiltInGenome("cpg"));
  return RunEpisode(p, p.genome.StartGenome());
}

// The start genome of --genes cpg drifts metres sideways on flat ground.
// When the stairs and pegs were 2 m wide it went round them and scored on
// both to 16 digits what it scores on flat; now they span its reach (the
// pegs between walls), so it meets them and scores less, and the rubble
// changes its score too (the stones help it).
TEST(TaskSuite, AGaitThatDriftsSidewaysCannotGoRoundTheObstacles) {
  const EvalResult flat = CpgStartGenomeOn("flat");
  ASSERT_FALSE(flat.failed);
  EXPECT_GT(flat.drift, 1.5) << "m sideways: no longer a drifting gait";
  for (const char* task : {"stairs", "pegs", "rubble"}) {
    SCOPED_TRACE(task);
    const EvalResult r = CpgStartGenomeOn(task);
    EXPECT_FALSE(r.failed);
    EXPECT_NE(r.distance, flat.distance);
    if (std::string(task) != "rubble") {
      EXPECT_LT(r.distance, flat.distance);
    }
  }
}

OptCommand ParseOpt(std::vector<std::string> args) {
  CLI::App app;
  OptCommand command;
  AddOptFlags(app, command);
  std::reverse(args.begin(), args.end());
  app.parse(args);
  return command;
}

TEST(TaskSuite, OptTakesATaskAndBuiltInGenes) {
  const std::string out = testing::TempDir("task_opt");
  const OptCommand c =
      ParseOpt({"--task", "pole", "--genes", "cpg", "--out", out});
  const OptSetup setup = PrepareOpt(c);
  EXPECT_EQ(setup.problem.episode.fitness.distance_mode, DistanceMode::kUp);
  EXPECT_EQ(setup.problem.scenario.scene_objects.size(), 1u);
  EXPECT_GE(setup.problem.genome.Find("cpg_coupling"), 0);
  const Gait g =
      GaitOfGenome(setup.problem, setup.problem.genome.StartGenome());
  ASSERT_TRUE(g.cpg.has_value());
  EXPECT_EQ(g.cpg->coupling, 4.0);
  // A scenario and a task at once, or neither, is refused by the parser.
  EXPECT_THROW(
      ParseOpt({"--task", "flat", "x.xml", "--genes", "sine", "--out", out}),
      CLI::ParseError);
  EXPECT_THROW(ParseOpt({"--genes", "sine", "--out", out}), CLI::ParseError);
  EXPECT_THROW(PrepareOpt(ParseOpt(
                   {"--task", "moon", "--genes", "sine", "--out", out + "/2"})),
               OptInputError);
  EXPECT_THROW(PrepareOpt(ParseOpt(
                   {"--task", "flat", "--genes", "walk", "--out", out + "/3"})),
               OptInputError);
}

}  // namespace
}  // namespace mrsim
