// Reads and writes scenario files in the MRSim XML layout (domain.md
// section 3). Every field round-trips; writing twice gives identical bytes.
#pragma once

#include <stdexcept>
#include <string>

#include "sim_core/scenario.h"

namespace mrsim {

// A bad scenario file. what() names the file, line, element path and what
// was expected, e.g.
//   "snake.xml:42: Scenario/robot/modules/Module[3]/joint/Kp: expected a
//    number, got 'fast'".
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads and validates a file; relative mesh/image paths resolve against the
// file's directory. Throws ScenarioError; nothing half-loads.
Scenario ReadScenarioFile(const std::string& path);

// As ReadScenarioFile, from a string. `name` is used in error messages;
// `base_dir` resolves relative paths.
Scenario ReadScenarioString(const std::string& xml, const std::string& name,
                            const std::string& base_dir);

// Writes the scenario in the given frame convention (recorded as the root
// attribute frame="z-up" or frame="unity-y-up").
std::string WriteScenarioString(const Scenario& scenario,
                                FrameConvention frame = FrameConvention::kZUp);
// Throws std::runtime_error naming the path when it cannot be written.
void WriteScenarioFile(const Scenario& scenario, const std::string& path,
                       FrameConvention frame = FrameConvention::kZUp);

}  // namespace mrsim
