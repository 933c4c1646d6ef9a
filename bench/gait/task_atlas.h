// The task suite's lines of the gait atlas: each task's own gait in the
// task's world (docs/tasks.md), measured like every other atlas line. Kept
// apart from AtlasEntries() because the tasks live in the optimiser, which
// the gait library must not depend on.
#pragma once

#include <vector>

#include "gait_controller/gait_atlas.h"

namespace mrsim {

// "task-flat", "task-slope", ... in TaskNames() order.
std::vector<AtlasEntry> TaskAtlasEntries();

// AtlasEntries() then TaskAtlasEntries(): every line of
// docs/gait_atlas.csv, in table order.
const std::vector<AtlasEntry>& AllAtlasEntries();

}  // namespace mrsim
