// mrsim-summary: one line on what a run did, from its scenario and its final
// checkpoint (mrsim-sim --checkpoint-on-exit).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "common/cli_exit.h"
#include "common/version.h"
#include "launcher/run_summary.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/scenario/scenario_xml.h"

int main(int argc, char** argv) {
  try {
    CLI::App app{
        "Prints how far each robot and movable scene object went in a run."};
    app.set_version_flag("--version",
                         std::string("mrsim-summary ") + mrsim::kVersion);
    std::string scenario_path;
    std::string checkpoint_path;
    app.add_option("scenario", scenario_path, "Scenario the run started from")
        ->required();
    app.add_option("checkpoint", checkpoint_path,
                   "Checkpoint written at the end of the run")
        ->required();
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return mrsim::CliParseExit(app, e);
    }
    const mrsim::Physics start(mrsim::ReadScenarioFile(scenario_path));
    const auto end = mrsim::LoadCheckpoint(checkpoint_path);
    std::cout << mrsim::FormatRunSummary(mrsim::SummarizeRun(start, *end))
              << "\n";
    return 0;
  } catch (const mrsim::ScenarioError& e) {
    std::fprintf(stderr, "mrsim-summary: %s\n", e.what());
    return 2;
  } catch (const mrsim::CheckpointError& e) {
    std::fprintf(stderr, "mrsim-summary: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrsim-summary: %s: %s\n", argv[argc - 1], e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-summary: %s\n", e.what());
    return 1;
  }
}
