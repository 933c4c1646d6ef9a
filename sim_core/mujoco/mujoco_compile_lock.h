// MuJoCo 2.2's XML parser and compiler keep global state: every
// mj_loadXML in the process holds this one lock, so models (and the
// validator's mesh checks) can be built from several threads.
#pragma once

#include <mutex>

namespace mrsim {

inline std::mutex& MujocoCompileMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace mrsim
