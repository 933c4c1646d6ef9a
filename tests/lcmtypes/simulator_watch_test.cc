#include "lcmtypes/runtime/simulator_watch.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mrsim {
namespace {

class SimulatorWatchTest : public ::testing::Test {
 protected:
  WallTime At(double s) const { return AfterSeconds(t0_, s); }
  sim_status_t Status(int8_t mode, const std::string& clock) const {
    sim_status_t s{};
    s.mode = mode;
    s.clock = clock;
    return s;
  }
  WallTime t0_{};
  std::vector<std::string> log_;
};

TEST_F(SimulatorWatchTest, WarnsOnceWhenNoSimulatorIsHeard) {
  SimulatorWatch watch("MRSIM_STATE_snake", false, t0_);
  watch.Tick(At(SimulatorWatch::kNoSimulatorWarning - 1), &log_);
  EXPECT_TRUE(log_.empty());
  watch.Tick(At(SimulatorWatch::kNoSimulatorWarning), &log_);
  watch.Tick(At(SimulatorWatch::kNoSimulatorWarning + 1), &log_);
  ASSERT_EQ(log_.size(), 1u);
  EXPECT_NE(log_[0].find("MRSIM_STATE_snake"), std::string::npos) << log_[0];
  EXPECT_FALSE(watch.stopped());
}

TEST_F(SimulatorWatchTest, ExitWithSimGivesUpWhenNoSimulatorEverCame) {
  SimulatorWatch watch("ch", true, t0_);
  watch.Tick(At(SimulatorWatch::kNoSimulatorGiveUp - 0.5), &log_);
  EXPECT_FALSE(watch.stopped());
  watch.Tick(At(SimulatorWatch::kNoSimulatorGiveUp), &log_);
  EXPECT_TRUE(watch.stopped());
  EXPECT_TRUE(watch.gave_up());
}

TEST_F(SimulatorWatchTest, ExitWithSimStopsWhenTheSimulatorFallsSilent) {
  SimulatorWatch watch("ch", true, t0_);
  watch.Heard(At(1));
  watch.Tick(At(1 + SimulatorWatch::kSimulatorSilence - 0.1), &log_);
  EXPECT_FALSE(watch.stopped());
  watch.Tick(At(1 + SimulatorWatch::kSimulatorSilence), &log_);
  EXPECT_TRUE(watch.stopped());
  EXPECT_FALSE(watch.gave_up());
}

TEST_F(SimulatorWatchTest, WithoutExitWithSimASilentSimulatorIsWaitedFor) {
  SimulatorWatch watch("ch", false, t0_);
  watch.Heard(At(1));
  watch.Tick(At(100), &log_);
  EXPECT_FALSE(watch.stopped());
}

TEST_F(SimulatorWatchTest, StatusGivesTheClockAndTheStop) {
  SimulatorWatch watch("ch", true, t0_);
  EXPECT_TRUE(watch.may_be_lockstep());  // not heard yet
  watch.OnStatus(Status(sim_status_t::RUNNING, "realtime"), At(1), &log_);
  EXPECT_FALSE(watch.may_be_lockstep());
  watch.OnStatus(Status(sim_status_t::RUNNING, "a-newer-clock"), At(2), &log_);
  EXPECT_TRUE(watch.may_be_lockstep());
  watch.OnStatus(Status(sim_status_t::STOPPING, "lockstep"), At(3), &log_);
  EXPECT_TRUE(watch.stopped());
  ASSERT_EQ(log_.size(), 1u);
}

}  // namespace
}  // namespace mrsim
