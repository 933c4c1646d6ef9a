// Owners for MuJoCo's C handles, so a throw anywhere frees them.
#pragma once

#include <mujoco/mujoco.h>

#include <memory>

namespace mrsim {

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
// A virtual file system allocated on the heap (it is about 2 MB) whose
// files are freed with it.
struct MjVfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    std::default_delete<mjVFS>()(vfs);
  }
};
using MjModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDataDeleter>;
using MjVfsPtr = std::unique_ptr<mjVFS, MjVfsDeleter>;

// An empty virtual file system.
inline MjVfsPtr MakeMjVfs() {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  return MjVfsPtr(vfs.release());
}

}  // namespace mrsim
