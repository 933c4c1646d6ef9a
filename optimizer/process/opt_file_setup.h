// `mrsim-opt FILE`: the optimisation setup saved in the design file
// (<optimization>, sim_core/scenario/optimization_settings.h) fills every
// setting the command line left out. Precedence: a flag given on the
// command line, then the file's value, then mrsim-opt's default
// (docs/optimizer.md, "The setup in the design file").
#pragma once

#include <functional>
#include <string>

#include "optimizer/process/opt_command.h"
#include "sim_core/scenario/optimization_settings.h"

namespace CLI {
class App;
}

namespace mrsim {

// Reads command->scenario_path (when the command names a scenario and not
// --task) and applies its <optimization> to the settings `app` did not
// parse from the command line; the file's <run> Lua script becomes what
// --controller lua runs. A file that does not read is left for PrepareOpt
// to report. Without --out the run folder is opt-<file or task name> in
// the working folder. Throws OptInputError "FILE:LINE:
// Scenario/optimization/FIELD: ..." for a value mrsim-opt does not accept.
void ApplyFileSetup(const CLI::App& app, OptCommand* command);

// The same from a setup already read. `given(flag)`: whether the command
// line gave that flag ("--generations"); `file` names it in errors,
// `line_of` gives the line of a field's path (0: unknown); `dir` is the
// design's folder (a lua:FILE or base gait file is looked for beside it).
void ApplyOptimizationSettings(
    const OptimizationSettings& settings,
    const std::function<bool(const std::string&)>& given,
    const std::string& file, const std::string& dir,
    const std::function<int(const std::string&)>& line_of, OptCommand* command);

}  // namespace mrsim
