// A checkpoint: the scenario plus the full physics state mid-run in one
// file (or string), so a run can be resumed bit for bit elsewhere.
//
// Format (text, docs/physics.md): a first line "mrsim-checkpoint 1", then
// "key: value" lines (time, base_dir, state = base64 of
// Physics::SaveState()), then "scenario-bytes: N", an empty line and the
// scenario XML (WriteScenarioString) as the remaining N bytes.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "sim_core/physics/physics.h"

namespace mrsim {

// A file that is not a readable checkpoint; what() names it and the cause.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string SaveCheckpointString(const Physics& physics);
// Throws std::runtime_error naming the path when it cannot be written; the
// file is written to a temporary name and renamed, so an old checkpoint is
// never left half-overwritten.
void SaveCheckpoint(const std::string& path, const Physics& physics);

// `name` is used in error messages. Throws CheckpointError.
std::unique_ptr<Physics> LoadCheckpointString(const std::string& text,
                                              const std::string& name);
std::unique_ptr<Physics> LoadCheckpoint(const std::string& path);

}  // namespace mrsim
