// A mesh file's bytes (a frame's OBJ or STL, a file or embedded) through
// the validator's mesh check: our OBJ reading, then MuJoCo's own reader.
// The first byte picks the format. An error naming it, or a mesh MuJoCo
// compiled; never a crash inside MuJoCo.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "sim_core/mesh/mesh_check.h"
#include "sim_core/mujoco/mujoco_handlers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool kHandlers = (mrsim::InstallMujocoHandlers(), true);
  (void)kHandlers;
  if (size < 1) return 0;
  const char* name = (data[0] & 1) ? "part.stl" : "part.obj";
  const std::vector<unsigned char> bytes(data + 1, data + size);
  try {
    mrsim::CheckMeshReadable(bytes, name, Eigen::Vector3d(0.01, 0.01, 0.01));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
