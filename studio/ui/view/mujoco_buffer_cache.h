// Keeps MuJoCo's large freed buffers for the next model, so a preview
// rebuild does not fault their pages in again. A long chain's mjData arena
// holds njmax^2 doubles (77 MB for 50 modules); on this kind of machine
// faulting fresh pages in cost more than the whole compile (docs/studio.md).
#pragma once

#include <cstddef>

namespace mrsim::studio {

// Installs the cache as MuJoCo's allocator (mju_user_malloc/mju_user_free)
// once per process; later calls do nothing. Safe however MuJoCo allocated
// before: blocks the cache did not hand out go back to free(), which is
// what MuJoCo's own allocator uses. Thread-safe.
void InstallMujocoBufferCache();

// Bytes held by freed blocks waiting for reuse (for tests).
size_t MujocoBufferCacheBytes();

}  // namespace mrsim::studio
