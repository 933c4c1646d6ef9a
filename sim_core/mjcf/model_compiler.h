// A scenario compiled into a MuJoCo model in memory, the one way the
// simulator and the viewer get their model: meshes and the terrain never
// touch the disk.
#pragma once

#include <string>

#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

// BuildMjcf(scenario, options) with its assets in memory and the height
// field filled after compiling (options.assets_in_memory and
// hfield_data_after_compile are set here), compiled. `info` may be null.
// Throws std::runtime_error with MuJoCo's message, or what the builder or
// the terrain loader throws. Safe to call from several threads.
MjModelPtr CompileScenarioModel(const Scenario& scenario, MjcfOptions options,
                                MjcfInfo* info = nullptr);

}  // namespace mrsim
