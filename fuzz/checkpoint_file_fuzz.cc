// The checkpoint reader on any bytes: a simulation it can step, or a
// CheckpointError (what mrsim-sim --load-checkpoint reports, exit 2).
#include <cstdint>
#include <string>

#include "sim_core/physics/checkpoint.h"
#include "sim_core/mujoco/mujoco_handlers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool kHandlers = (mrsim::InstallMujocoHandlers(), true);
  (void)kHandlers;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto physics = mrsim::LoadCheckpointString(text, "fuzz.checkpoint");
    physics->Step();
  } catch (const mrsim::CheckpointError&) {
  }
  return 0;
}
