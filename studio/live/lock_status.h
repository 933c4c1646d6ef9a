// The locks of a running robot as the Run panel lists them: each lock the
// simulator reports (robot_state_t's lock_names and lock_attached), its
// break force from the scenario, and whether a released lock was detached
// from the window or broke under load (a breakable lock the user did not
// detach). The Detach/Attach buttons send LiveSession::SetLockAttached.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "mrsim/robot_state_t.hpp"
#include "sim_core/scenario/scenario.h"

namespace mrsim::studio {

struct LockStatus {
  std::string name;  // as the simulator names it (guid or "lock<k>")
  bool attached = true;
  double break_force = 0;  // N, 0: never breaks (or not known)
  bool broken = false;     // released by the physics, not by the user
  // "attached, breaks at 40 N", "detached", "broken (over 40 N)".
  std::string Describe() const;
};

// `robot`: the scenario's robot of that name (null: break forces unknown).
// `detached`: the locks the user detached and did not attach again.
std::vector<LockStatus> LockStatuses(const robot_state_t& state,
                                     const Robot* robot,
                                     const std::set<std::string>& detached);

}  // namespace mrsim::studio
