// The Run panel's locks: detach and attach go to the simulator as
// sim_control_t, and each lock is listed attached, detached or broken with
// its break force.
#include "studio/live/lock_status.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <variant>

#include "studio/live/live_session.h"

namespace mrsim::studio {
namespace {

robot_state_t StateWithLocks() {
  robot_state_t s{};
  s.robot = "snake";
  s.num_locks = 3;
  s.lock_names = {"plate", "lock1", "sm0/lock0"};
  s.lock_attached = {true, false, false};
  return s;
}

Robot SnakeWithLocks() {
  Robot r;
  r.name = "snake";
  Joint plate;
  plate.guid = "plate";
  plate.type = JointType::kLock;
  plate.break_force = 40;
  Joint unnamed = plate;
  unnamed.guid = "";
  unnamed.break_force = 25;
  r.locks = {plate, unnamed};
  return r;
}

TEST(LockStatus, ReleasedBreakableLockTheUserDidNotDetachIsBroken) {
  const Robot robot = SnakeWithLocks();
  const auto locks = LockStatuses(StateWithLocks(), &robot, {"sm0/lock0"});
  ASSERT_EQ(locks.size(), 3u);
  EXPECT_EQ(locks[0].Describe(), "attached, breaks at 40 N");
  EXPECT_EQ(locks[1].break_force, 25);  // "lock1": the second, no guid
  EXPECT_TRUE(locks[1].broken);
  EXPECT_EQ(locks[1].Describe(), "broken (over 25 N)");
  EXPECT_FALSE(locks[2].broken);
  EXPECT_EQ(locks[2].Describe(), "detached");
}

TEST(LockStatus, WithoutTheScenarioBreakForcesAreUnknown) {
  const auto locks = LockStatuses(StateWithLocks(), nullptr, {});
  ASSERT_EQ(locks.size(), 3u);
  EXPECT_EQ(locks[0].Describe(), "attached, never breaks");
  EXPECT_EQ(locks[1].Describe(), "detached");
}

TEST(LockStatus, AStateClaimingMoreLocksThanItCarriesIsCut) {
  robot_state_t s = StateWithLocks();
  s.num_locks = 100;
  EXPECT_EQ(LockStatuses(s, nullptr, {}).size(), 3u);
}

TEST(LockStatus, DetachAndAttachAreSimControlRequests) {
  LiveSessionOptions options;
  options.prefix = "TEST";
  LiveSession session(options);
  StudioOutbox out;
  const WallTime now{};
  const int64_t seq =
      session.SetLockAttached("snake", "plate", false, now, &out);
  session.SetLockAttached("snake", "plate", true, now, &out);
  ASSERT_EQ(out.messages.size(), 2u);
  EXPECT_EQ(out.messages[0].first, "TEST_SIM_CONTROL");
  const auto& d = std::get<sim_control_t>(out.messages[0].second);
  EXPECT_EQ(d.command, int8_t{sim_control_t::DETACH});
  EXPECT_EQ(d.robot, "snake");
  EXPECT_EQ(d.lock, "plate");
  EXPECT_EQ(d.seq, seq);
  EXPECT_EQ(std::get<sim_control_t>(out.messages[1].second).command,
            int8_t{sim_control_t::ATTACH});
  EXPECT_EQ(session.request(seq)->what, "detach snake/plate");
  EXPECT_THROW(session.SetLockAttached("snake", "", true, now, &out),
               std::invalid_argument);
}

}  // namespace
}  // namespace mrsim::studio
