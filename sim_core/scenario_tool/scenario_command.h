// mrsim-scenario as library code: its subcommands and flags, and what each
// does with the files named. main only parses and reports.
#pragma once

#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim_core/scenario/chain_builder.h"

namespace CLI {
class App;
}

namespace mrsim {

enum class ScenarioAction {
  kNone,
  kValidate,
  kInfo,
  kSchema,
  kExport,
  kConvert,
  kNew,
  kExportStl
};

// Everything the command line sets.
struct ScenarioCommand {
  ScenarioAction action = ScenarioAction::kNone;
  std::string file;      // validate, info, export-mjcf; convert's IN
  std::string out_path;  // "" or "-": stdout; export-stl: the directory
  // convert
  double scale = 1.0;
  std::string from_frame;  // "": the file's own frame attribute
  std::string to_frame = "z-up";
  // new
  ChainOptions chain;
  std::string pattern = "pitch";
  std::string sensors = "none";
  std::string ground = "ground";
  double frame_size = ChainOptions{}.frame_size.x();
  std::vector<double> origin;      // empty or X Y Z
  std::optional<double> friction;  // unset: no ContactFriction
};

// Registers the subcommands and their flags on `app`, writing into
// `command` (its action is set by the subcommand given).
void AddScenarioFlags(CLI::App& app, ScenarioCommand& command);

// Bad input on the command line or in a file (mrsim-scenario exits 2).
class ScenarioInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Does what `command` asks: results on `out` (or the output file, then
// "wrote FILE" on `info`). Throws ScenarioInputError for bad input (a
// ScenarioError from the reader among them) and std::runtime_error when
// an output cannot be written.
void RunScenarioCommand(const ScenarioCommand& command, std::ostream& out,
                        std::ostream& info);

// --sensors: "none", "all" (in front of module 0 and after every module),
// "between" (between consecutive modules) or a comma list of module numbers
// after which a sensor module goes (-1 = in front of module 0).
std::vector<int> ParseSensorSpec(const std::string& spec, int modules);

}  // namespace mrsim
