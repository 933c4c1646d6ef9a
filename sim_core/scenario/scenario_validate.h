// The one validator of scenarios: every rule a scenario must meet for the
// simulator to run it. The file reader, BuildMjcf and Physics all call
// ValidateScenario, so `mrsim-scenario validate` accepts exactly what the
// simulator runs. Field limits come from the schema (scenario_schema.h).
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// A bad scenario. what() names the file, line, element path and what was
// expected, e.g.
//   "snake.xml:42: Scenario/robot[1]/modules/Module[3]/joint/Kp: expected a
//    number, got 'fast'"
// or, for a scenario built in memory, "Scenario/robot[1]/...: ...".
class ScenarioError : public std::runtime_error {
 public:
  // A message already in the format above.
  explicit ScenarioError(const std::string& what)
      : std::runtime_error(what), message_(what) {}
  ScenarioError(const std::string& file, int line, std::string path,
                std::string message);

  // The element path ("Scenario/robot[1]/...") or "" when not known.
  const std::string& path() const { return path_; }
  // What was expected, without file, line and path.
  const std::string& message() const { return message_; }
  int line() const { return line_; }

 private:
  std::string path_;
  std::string message_;
  int line_ = 0;
};

// Where the parts and fields of a scenario came from: element path (as in
// errors) -> line in `file`. Filled by the reader.
struct ScenarioSource {
  std::string file;
  std::map<std::string, int> lines;

  // The line of `path`, or of its nearest recorded ancestor (a field left
  // out of a file is reported at its part's element).
  int LineOf(const std::string& path) const;
};

// Throws ScenarioError at the first broken rule, in file order: field
// limits (scenario_schema.h), unique and non-empty guids, unique robot
// names and module numbers, joints naming existing parts, hinges that do
// not close loops, robots whose parts hang together, readable mesh files
// and height images (resolved against scenario.base_dir), at most six
// distance sensors. With a source, errors carry file:line.
void ValidateScenario(const Scenario& scenario,
                      const ScenarioSource* source = nullptr);

// What a valid scenario holds that runs but is likely not what its author
// meant: a distance sensor whose ray starts inside another part of its
// robot and would read about 0 the whole run. Told, never refused, so the
// files the original MRSim ran load; programs print them.
struct ScenarioWarning {
  std::string path;     // element path, as in errors
  std::string message;  // what, without file, line and path
  // "file:line: path: warning: message" (without a source: "path: ...").
  std::string text;
};

// The warnings of `scenario`, in file order. Throws ScenarioError as
// ValidateScenario does when the scenario is not valid.
std::vector<ScenarioWarning> ScenarioWarnings(
    const Scenario& scenario, const ScenarioSource* source = nullptr);

}  // namespace mrsim
