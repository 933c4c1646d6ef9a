// Owners for MuJoCo's C handles, so a throw anywhere frees them.
#pragma once

#include <mujoco/mujoco.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

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

// Adds `size` bytes as file `name`. Throws std::runtime_error when the file
// system is full (MuJoCo 2.2 holds up to 2000 files).
inline void AddMjVfsFile(mjVFS* vfs, const std::string& name, const void* bytes,
                         size_t size) {
  if (mj_makeEmptyFileVFS(vfs, name.c_str(), static_cast<int>(size)) != 0) {
    throw std::runtime_error("cannot hold '" + name + "' in memory");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs, name.c_str())], bytes, size);
}

}  // namespace mrsim
