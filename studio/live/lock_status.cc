#include "studio/live/lock_status.h"

#include <fmt/format.h>

#include <algorithm>

namespace mrsim::studio {
namespace {

// A lock's break force by the name the simulator gives it: its guid when
// that names one lock of the robot, else "lock<k>" (mjcf_builder.h,
// MjcfLock). Implicit sensor-module locks never break.
double BreakForce(const Robot& robot, const std::string& name) {
  for (size_t k = 0; k < robot.locks.size(); ++k) {
    const Joint& lock = robot.locks[k];
    const bool unique =
        !lock.guid.empty() &&
        std::count_if(robot.locks.begin(), robot.locks.end(),
                      [&](const Joint& j) { return j.guid == lock.guid; }) == 1;
    const std::string own = unique ? lock.guid : "lock" + std::to_string(k);
    if (own == name) return lock.break_force;
  }
  return 0;
}

}  // namespace

std::string LockStatus::Describe() const {
  if (attached) {
    return break_force > 0
               ? fmt::format("attached, breaks at {:g} N", break_force)
               : std::string("attached, never breaks");
  }
  return broken ? fmt::format("broken (over {:g} N)", break_force)
                : std::string("detached");
}

std::vector<LockStatus> LockStatuses(const robot_state_t& state,
                                     const Robot* robot,
                                     const std::set<std::string>& detached) {
  std::vector<LockStatus> out;
  const size_t n =
      std::min({static_cast<size_t>(std::max(state.num_locks, 0)),
                state.lock_names.size(), state.lock_attached.size()});
  for (size_t i = 0; i < n; ++i) {
    LockStatus s;
    s.name = state.lock_names[i];
    s.attached = state.lock_attached[i];
    if (robot) s.break_force = BreakForce(*robot, s.name);
    s.broken = !s.attached && s.break_force > 0 && !detached.count(s.name);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace mrsim::studio
