#include "studio/ui/view/mujoco_buffer_cache.h"

#include <mujoco/mujoco.h>

#include <cstdlib>
#include <map>
#include <mutex>

namespace mrsim::studio {
namespace {

// Smaller blocks are cheap to fault in and many: left to malloc.
constexpr size_t kLarge = size_t{4} << 20;
// Freed large blocks kept at most; the oldest go first.
constexpr size_t kMaxCached = size_t{512} << 20;

struct Cache {
  std::mutex mutex;
  std::map<void*, size_t> live;       // large blocks handed out: capacity
  std::multimap<size_t, void*> idle;  // capacity -> freed block
  size_t idle_bytes = 0;
};

Cache& TheCache() {
  static Cache* cache = new Cache;  // MuJoCo may free after static exit
  return *cache;
}

void* Allocate(size_t size) {
  // MuJoCo's own allocator pads to 8 bytes and aligns to 8.
  const size_t padded = (size + 63) / 64 * 64;
  if (padded < kLarge) return std::aligned_alloc(64, padded);
  Cache& c = TheCache();
  std::lock_guard<std::mutex> lock(c.mutex);
  // The smallest idle block that fits; only pages a model touches are
  // resident, so a larger block costs address space, not memory.
  auto it = c.idle.lower_bound(padded);
  if (it != c.idle.end()) {
    void* block = it->second;
    c.live[block] = it->first;
    c.idle_bytes -= it->first;
    c.idle.erase(it);
    return block;
  }
  // Room to grow: the next model of a chain edited part by part is a bit
  // larger and still fits.
  const size_t capacity = padded * 2;
  void* block = std::aligned_alloc(64, capacity);
  if (block != nullptr) c.live[block] = capacity;
  return block;
}

void Free(void* block) {
  if (block == nullptr) return;
  Cache& c = TheCache();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    auto it = c.live.find(block);
    if (it != c.live.end()) {
      const size_t capacity = it->second;
      c.live.erase(it);
      c.idle.emplace(capacity, block);
      c.idle_bytes += capacity;
      // Over the limit: drop the largest blocks first (they are the rarest).
      while (c.idle_bytes > kMaxCached && !c.idle.empty()) {
        auto last = std::prev(c.idle.end());
        c.idle_bytes -= last->first;
        std::free(last->second);
        c.idle.erase(last);
      }
      return;
    }
  }
  std::free(block);
}

}  // namespace

void InstallMujocoBufferCache() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (mju_user_malloc == nullptr && mju_user_free == nullptr) {
      mju_user_malloc = Allocate;
      mju_user_free = Free;
    }
  });
}

size_t MujocoBufferCacheBytes() {
  Cache& c = TheCache();
  std::lock_guard<std::mutex> lock(c.mutex);
  return c.idle_bytes;
}

}  // namespace mrsim::studio
