// The simulator as an LCM service: publishes every robot's state once per
// control period, applies the newest valid joint command per robot, answers
// sim_control_t requests and reports sim_status_t. Holds the lcm::LCM and
// the Physics by reference; main owns both.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "mrsim/joint_command_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/physics.h"
#include "sim_core/sim_process/command_filter.h"
#include "sim_core/sim_process/sim_options.h"

namespace mrsim {

// Subscription queue capacities (messages). LCM 1.3.1 keeps 30 per
// subscription and drops the newest beyond; see docs/sim.md for why these.
inline constexpr int kCommandQueueCapacity = 2000;
inline constexpr int kControlQueueCapacity = 200;

// Why Run returned.
enum class StopReason { kQuit, kDuration, kSignal };
const char* ToString(StopReason reason);

class SimServer {
 public:
  // Subscribes to <prefix>_COMMAND_* and <prefix>_SIM_CONTROL. Throws
  // std::invalid_argument on bad options.
  // Warnings (lockstep timeouts, physics errors) go to `log`.
  SimServer(lcm::LCM& lcm, std::unique_ptr<Physics> physics, SimOptions options,
            std::ostream& log);
  ~SimServer();
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  // Runs until QUIT, the duration, or stop_requested() returns true (checked
  // at least every 50 ms). Writes --checkpoint-on-exit before returning.
  StopReason Run(const std::function<bool()>& stop_requested);

  const Physics& physics() const { return *physics_; }

  // Checkpoint files (sim_core/checkpoint.h): the scenario plus the exact
  // state. Loading needs the same scenario as the running one. Throw
  // std::runtime_error naming the path.
  void SaveCheckpoint(const std::string& path) const;
  void LoadCheckpoint(const std::string& path);

  int steps_per_period() const { return steps_per_period_; }
  // Control period (s of sim time): steps_per_period * timestep.
  double period() const { return period_; }

  // Why the --checkpoint-on-exit could not be written (empty when it was).
  const std::string& exit_checkpoint_error() const {
    return exit_checkpoint_error_;
  }

  // The latest status (counters, mode, sim time).
  sim_status_t status() const;
  // One line for the end of a run.
  std::string Summary(StopReason reason) const;

 private:
  using Clock = std::chrono::steady_clock;

  void OnCommand(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnControl(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void HandleCommand(const joint_command_t& cmd, const std::string& channel);
  void HandleControl(const lcm::ReceiveBuffer* rbuf);

  void Handle(int timeout_ms);
  bool LockstepAnswered() const;
  void CheckLockstepWait();
  void RunPeriod();
  void PublishStates();
  void SendStates();
  void PublishStatus();
  void MaybePublishStatus();
  void Reanchor();
  void ClearPending();
  void Fail(const std::string& error);

  lcm::LCM& lcm_;
  std::unique_ptr<Physics> physics_;
  SimOptions options_;
  std::ostream& log_;
  int steps_per_period_ = 1;
  double period_ = 0.01;  // s of sim time
  std::vector<lcm::Subscription*> subscriptions_;
  CommandFilter filter_;

  bool paused_ = false;
  bool quit_ = false;
  int64_t steps_pending_ = 0;  // control periods still to run after STEP
  int64_t state_seq_ = -1;     // seq of the newest state published
  int64_t status_seq_ = 0;
  int64_t steps_ = 0;

  // Pending command per robot (applied at the start of the next period) and
  // the index in --controllers of its sender (lockstep).
  std::vector<std::optional<joint_command_t>> pending_;
  std::vector<int> pending_controller_;
  // Lockstep: robots each controller has commanded, and those it answered
  // for the current state.
  std::map<std::string, std::vector<bool>> controller_robots_;
  std::map<std::string, std::vector<bool>> answered_;
  Clock::time_point wait_start_;
  Clock::time_point last_republish_;
  int timeout_warnings_ = 0;
  std::string waiting_for_;

  // Realtime pacing: period k of the current run starts at anchor + k *
  // period / speed.
  Clock::time_point anchor_;
  int64_t periods_since_anchor_ = 0;

  // Whole-run pace for the summary.
  bool ran_period_ = false;
  Clock::time_point first_period_wall_;
  Clock::time_point run_end_wall_;
  double advanced_ = 0;  // s of sim time stepped (resets do not undo it)

  // Status.
  Clock::time_point last_status_;
  double last_status_sim_time_ = 0;
  double real_time_factor_ = 0;
  int64_t commands_applied_ = 0;
  int64_t rejected_joint_count_ = 0;
  int64_t rejected_value_ = 0;
  int64_t rejected_robot_ = 0;
  int64_t rejected_seq_ = 0;
  int64_t rejected_sender_ = 0;
  int64_t malformed_ = 0;
  int64_t superseded_ = 0;
  int64_t control_gaps_ = 0;
  std::map<std::string, int64_t> control_last_seq_;
  int64_t control_seq_ = -1;
  bool control_ok_ = true;
  std::string last_error_;
  std::string exit_checkpoint_error_;
};

}  // namespace mrsim
