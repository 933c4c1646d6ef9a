// mrsim-scenario: validate, inspect, convert, export and generate scenario
// files (the work is in scenario_command.h). Exit codes: 0 success, 2 bad
// input (the error on stderr), 1 when an output cannot be written or
// anything else fails.
#include <CLI/CLI.hpp>
#include <iostream>

#include "common/cli_exit.h"
#include "common/version.h"
#include "sim_core/scenario_tool/scenario_command.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Validate, inspect, convert, export and generate mrsim "
      "scenario files (docs/scenario.md)."};
  app.set_version_flag("--version",
                       std::string("mrsim-scenario ") + mrsim::kVersion);
  mrsim::ScenarioCommand command;
  mrsim::AddScenarioFlags(app, command);
  const auto known = app.get_subcommands([&](const CLI::App* sub) {
    return argc > 1 && sub->get_name() == argv[1];
  });
  if (argc > 1 && argv[1][0] != '-' && known.empty()) {
    const std::string nearest = mrsim::NearestSubcommand(app, argv[1]);
    std::cerr << "error: unknown subcommand '" << argv[1] << "'"
              << (nearest.empty() ? "" : " (did you mean " + nearest + "?)")
              << "; expected validate, info, schema, export-mjcf, "
                 "export-stl, convert or new (--help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    mrsim::RunScenarioCommand(command, std::cout, std::cerr);
    return 0;
  } catch (const mrsim::ScenarioInputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
