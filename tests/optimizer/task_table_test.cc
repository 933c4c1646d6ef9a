// The tables of docs/tasks.md and the rest of mrsim-tasks' output, made
// from the task suite (the docs check, Docs.TasksTablesAreTheCommands,
// compares them with docs/tasks.md).
#include "optimizer/episode/task_table.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>

#include "gait_controller/gait_presets.h"
#include "optimizer/episode/task.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

TEST(TaskTable, TheTaskListHasARowForEveryTaskWithWhatItScores) {
  const std::string table = TaskListMarkdown();
  EXPECT_EQ(table.rfind("| task | world | fitness (m) | episode |\n", 0), 0u);
  for (const std::string& name : TaskNames()) {
    const Task t = MakeTask(name);
    const std::string row =
        fmt::format("| {} | {} | {} |", name, t.world, TaskFitnessText(t));
    EXPECT_NE(table.find(row), std::string::npos) << row;
  }
  EXPECT_NE(table.find("| CoM rise along +z | 30 s |"), std::string::npos);
}

TEST(TaskTable, EveryComparedGaitIsTheTasksOwnOrAPreset) {
  const std::vector<std::string>& gaits = TableGaits();
  ASSERT_FALSE(gaits.empty());
  EXPECT_EQ(gaits[0], "task");
  for (size_t i = 1; i < gaits.size(); ++i) {
    EXPECT_TRUE(FindGaitPreset(gaits[i]).has_value()) << gaits[i];
  }
  EXPECT_EQ(std::set<std::string>(gaits.begin(), gaits.end()).size(),
            gaits.size());
}

TEST(TaskTable, TheCommandScoresAGaitAsEvaluateTaskDoes) {
  TaskCommand c;
  c.task = "flat";
  c.gait = "forward";
  c.seconds = 2;
  const EvalResult r =
      EvaluateTask(MakeTask("flat"), *FindGaitPreset("forward"), 2);
  EXPECT_EQ(RunTaskCommand(c),
            fmt::format("flat forward forward: {:.3f} m\n", r.distance));
}

TEST(TaskTable, TheCommandWritesTheTasksScenario) {
  TaskCommand c;
  c.task = "stairs";
  c.write = testing::TempDir() + "stairs.xml";
  EXPECT_EQ(RunTaskCommand(c), "wrote " + c.write + "\n");
  EXPECT_EQ(WriteScenarioString(ReadScenarioFile(c.write)),
            WriteScenarioString(MakeTask("stairs").scenario));
}

TEST(TaskTable, TheCommandRefusesAnUnknownTask) {
  TaskCommand c;
  c.task = "moon";
  EXPECT_THROW(RunTaskCommand(c), TaskError);
}

}  // namespace
}  // namespace mrsim
