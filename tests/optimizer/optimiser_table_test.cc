// The optimiser table of docs/tasks.md is mrsim-opt's command line run on
// each task (the full table is the slow docs check,
// Docs.TasksOptimiserTableIsTheCommand; these hold what each cell runs).
#include "optimizer/process/optimiser_table.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <set>

#include "optimizer/process/opt_command.h"

namespace mrsim {
namespace {

TEST(OptimiserTable, ACellRunsTheDocsCommandLineWithTheTasksEpisode) {
  const OptimiserTableRow& sine = OptimiserTableRows()[0];
  EXPECT_EQ(
      OptimiserCellArguments("pole", sine, "out/pole-sine"),
      (std::vector<std::string>{
          "--task", "pole", "--genes", "sine", "--algorithm", "cmaes",
          "--population", "8", "--generations", "3", "--seed", "1", "--episode",
          "30", "--workers", "local:1", "--out", "out/pole-sine"}));
  // mrsim-opt's own flags take every cell's arguments.
  for (const OptimiserTableRow& row : OptimiserTableRows()) {
    OptCommand c;
    CLI::App app;
    AddOptFlags(app, c);
    std::vector<std::string> args = OptimiserCellArguments("flat", row, "o");
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    ASSERT_NO_THROW(app.parse(reversed)) << row.label;
    EXPECT_EQ(c.episode.duration, 20) << row.label;
    EXPECT_EQ(c.algorithm.population, 8) << row.label;
    EXPECT_EQ(c.workers, "local:1") << row.label;
  }
}

TEST(OptimiserTable, EveryRowIsLabelledWithItsOwnFlag) {
  std::set<std::string> labels;
  for (const OptimiserTableRow& row : OptimiserTableRows()) {
    ASSERT_EQ(row.flags.size(), 2u);
    EXPECT_NE(row.label.find("`" + row.flags[0] + " " + row.flags[1] + "`"),
              std::string::npos)
        << row.label;
    labels.insert(row.label);
  }
  EXPECT_EQ(labels.size(), 4u);
}

TEST(OptimiserTable, AScriptThatIsNotThereIsAnInputError) {
  const OptimiserTableRow row{"missing",
                              {"--controller", "lua:/nonexistent/x.lua"}};
  EXPECT_THROW(RunOptimiserCell("flat", row, testing::TempDir()),
               OptInputError);
}

}  // namespace
}  // namespace mrsim
