// The Run panel's Locks section: every lock of the followed robot, its
// state (attached, detached, broken) and break force, with a Detach or
// Attach button each (sim_control_t DETACH / ATTACH).
// Part of LivePanel (live_panel.h), one file per section.
#include "studio/live/lock_status.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

void LivePanel::DrawLocks() {
  const LiveRobot* robot =
      link_ && !followed_.empty() ? session_->robot(followed_) : nullptr;
  if (robot == nullptr || robot->states == 0) {
    ImGui::TextDisabled("no robot heard");
    return;
  }
  // Break forces from the scenario that runs (the design as Run saved it,
  // or the replayed body).
  const Robot* design_robot = nullptr;
  if (const Scenario* s = live_scenario()) {
    for (const Robot& r : s->robots) {
      if (r.name == followed_) design_robot = &r;
    }
  }
  std::set<std::string>& detached = detached_locks_[followed_];
  const std::vector<LockStatus> locks =
      LockStatuses(robot->state, design_robot, detached);
  if (locks.empty()) ImGui::TextDisabled("%s has no locks", followed_.c_str());
  for (const LockStatus& lock : locks) {
    ImGui::PushID(lock.name.c_str());
    const std::string label = lock.attached ? "Detach" : "Attach";
    const bool pressed = ImGui::Button(label.c_str(), ImVec2(60, 0));
    RecordItem(layout_, label + " " + lock.name);
    if (pressed) {
      Send([&](StudioOutbox* out) {
        session_->SetLockAttached(followed_, lock.name, !lock.attached,
                                  WallClock::now(), out);
      });
      if (lock.attached) {
        detached.insert(lock.name);
      } else {
        detached.erase(lock.name);
      }
    }
    ImGui::SameLine();
    const ImVec4 colour = lock.broken     ? ImVec4(1, 0.45f, 0.35f, 1)
                          : lock.attached ? ImVec4(0.75f, 0.9f, 0.75f, 1)
                                          : ImVec4(0.9f, 0.8f, 0.5f, 1);
    ImGui::TextColored(colour, "%s: %s", lock.name.c_str(),
                       lock.Describe().c_str());
    ImGui::PopID();
  }
}

}  // namespace mrsim::studio
