// Reads and writes scenario files in the MRSim XML layout (domain.md
// section 3), including files the original wrote (section 8). Every field
// round-trips; writing twice gives identical bytes. Field names, types and
// limits come from the schema (scenario_schema.h); the reader ends with
// ValidateScenario (scenario_validate.h).
#pragma once

#include <optional>
#include <string>

#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario/scenario_validate.h"

namespace mrsim {

struct ScenarioReadOptions {
  // The frame of a file that has no frame attribute, e.g. kUnityYUp for a
  // file the original wrote. Unset: such a file is Z-up. A file whose
  // attribute says otherwise is an error.
  std::optional<FrameConvention> frame;
  // Multiplies every length the file gives (positions, sizes, ray lengths,
  // terrain extent and height; never gravity or masses), e.g. 0.01 for a
  // file in centimetres. Fields the file leaves out take the model's
  // defaults, which are already in metres.
  double length_scale = 1.0;
  // When set, receives the file and the line of every element read, so a
  // later check (overlap_check.h) can name lines as the reader does.
  ScenarioSource* source_out = nullptr;
};

// What the original MRSim wrote (its .NET namespaces and no frame
// attribute): Unity's Y-up frame in centimetres, read with
// kOriginalMrsimReadOptions. Reading one without options is an error
// saying so. False for a file that does not parse.
bool IsOriginalMrsimFile(const std::string& path);
inline const ScenarioReadOptions kOriginalMrsimReadOptions{
    FrameConvention::kUnityYUp, 0.01};

// Reads and validates a file; relative mesh/image paths resolve against the
// file's directory. Throws ScenarioError ("file:line: path: what"); nothing
// half-loads.
Scenario ReadScenarioFile(const std::string& path,
                          const ScenarioReadOptions& options = {});

// As ReadScenarioFile, from a string. `name` is used in error messages;
// `base_dir` resolves relative paths.
Scenario ReadScenarioString(const std::string& xml, const std::string& name,
                            const std::string& base_dir,
                            const ScenarioReadOptions& options = {});

// Writes the scenario in the given frame convention (recorded as the root
// attribute frame="z-up" or frame="unity-y-up").
std::string WriteScenarioString(const Scenario& scenario,
                                FrameConvention frame = FrameConvention::kZUp);
// Throws std::runtime_error naming the path when it cannot be written.
void WriteScenarioFile(const Scenario& scenario, const std::string& path,
                       FrameConvention frame = FrameConvention::kZUp);

}  // namespace mrsim
