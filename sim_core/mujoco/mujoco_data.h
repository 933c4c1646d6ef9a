// Making and resetting an mjData whose resident memory is what the steps
// use, not what MuJoCo 2.2 reserves.
//
// MuJoCo 2.2 sizes its constraint arrays from `njmax` (`efc_AR` and its
// column indices as njmax^2, the Jacobians as njmax x nv) and writes zeros
// over all of them when it makes or resets an mjData, so a 200-module chain
// (6 600 rows) holds 560 MB resident although the Newton and CG solvers
// never touch `efc_AR` (only PGS and noslip do) and a sparse Jacobian fills
// a fraction of its arrays. These functions hand the pages of those arrays
// back to the OS right after MuJoCo zeroed them: a page read later is zero,
// as it was, and one written comes back on demand, so results do not
// change (tested bit for bit).
#pragma once

#include <mujoco/mujoco.h>

#include <cstddef>

#include "sim_core/mujoco/mujoco_ptr.h"

namespace mrsim {

// mj_makeData, then ReleaseZeroedConstraintPages. Null when MuJoCo cannot
// allocate the data.
MjDataPtr MakeMjData(const mjModel* m);

// mj_resetData, then ReleaseZeroedConstraintPages.
void ResetMjData(const mjModel* m, mjData* d);

// Gives back the whole pages of `d`'s constraint arrays (sized by njmax).
// Only right after MuJoCo zeroed them: their contents become zeros.
void ReleaseZeroedConstraintPages(const mjModel* m, mjData* d);

// Bytes of `d`'s constraint arrays resident in memory now (mincore), for
// tests and benchmarks.
size_t ResidentConstraintBytes(const mjModel* m, const mjData* d);

}  // namespace mrsim
