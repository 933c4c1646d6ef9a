#include "sim_core/mujoco/mujoco_data.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <vector>

namespace mrsim {
namespace {

struct Span {
  const void* begin;
  size_t bytes;
};

// The arrays MuJoCo 2.2 sizes by njmax (mjxmacro.h) that are large enough
// to matter: njmax^2 and njmax x nv.
std::vector<Span> ConstraintArrays(const mjModel* m, const mjData* d) {
  const size_t rows = static_cast<size_t>(m->njmax);
  const size_t nv = static_cast<size_t>(m->nv);
  return {{d->efc_AR, sizeof(mjtNum) * rows * rows},
          {d->efc_AR_colind, sizeof(int) * rows * rows},
          {d->efc_J, sizeof(mjtNum) * rows * nv},
          {d->efc_J_colind, sizeof(int) * rows * nv},
          {d->efc_JT, sizeof(mjtNum) * rows * nv},
          {d->efc_JT_colind, sizeof(int) * rows * nv}};
}

size_t PageSize() { return static_cast<size_t>(sysconf(_SC_PAGESIZE)); }

// The whole pages inside [begin, begin + bytes), as [first, last).
bool InnerPages(const Span& s, uintptr_t* first, uintptr_t* last) {
  if (s.begin == nullptr || s.bytes == 0) return false;
  const uintptr_t page = PageSize();
  const uintptr_t begin = reinterpret_cast<uintptr_t>(s.begin);
  *first = (begin + page - 1) / page * page;
  *last = (begin + s.bytes) / page * page;
  return *last > *first;
}

}  // namespace

MjDataPtr MakeMjData(const mjModel* m) {
  MjDataPtr d(mj_makeData(m));
  if (d) ReleaseZeroedConstraintPages(m, d.get());
  return d;
}

void ResetMjData(const mjModel* m, mjData* d) {
  mj_resetData(m, d);
  ReleaseZeroedConstraintPages(m, d);
}

void ReleaseZeroedConstraintPages(const mjModel* m, mjData* d) {
  for (const Span& s : ConstraintArrays(m, d)) {
    uintptr_t first = 0, last = 0;
    if (!InnerPages(s, &first, &last)) continue;
    // Private anonymous memory (malloc's): dropped pages read as zeros. On
    // failure the pages simply stay resident.
    madvise(reinterpret_cast<void*>(first), last - first, MADV_DONTNEED);
  }
}

size_t ResidentConstraintBytes(const mjModel* m, const mjData* d) {
  const size_t page = PageSize();
  size_t resident = 0;
  for (const Span& s : ConstraintArrays(m, d)) {
    uintptr_t first = 0, last = 0;
    if (!InnerPages(s, &first, &last)) continue;
    std::vector<unsigned char> in_core((last - first) / page);
    if (mincore(reinterpret_cast<void*>(first), last - first, in_core.data()) !=
        0) {
      continue;
    }
    for (unsigned char c : in_core) resident += (c & 1) ? page : 0;
  }
  return resident;
}

}  // namespace mrsim
