// The simulator's logic as a plain state machine: decoded messages and the
// current wall time in, messages to publish and the next deadline out. It
// owns the Physics and knows nothing of LCM or clocks, so lockstep, pacing,
// re-sends and every counter are tested in process with a fake clock
// (SimServer is the thin adapter that owns the lcm::LCM and steady_clock).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mrsim/joint_command_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/physics/physics.h"
#include "sim_core/sim_process/command_filter.h"
#include "sim_core/sim_process/sim_options.h"
#include "sim_core/sim_process/sim_outbox.h"

namespace mrsim {

// Why the node stopped.
// kPhysicsFailed: the physics failed in a batch run (--duration); an
// interactive run pauses instead, for RESET or LOAD_CHECKPOINT.
enum class StopReason { kQuit, kDuration, kSignal, kPhysicsFailed };
const char* ToString(StopReason reason);

class SimNode {
 public:
  // While a lockstep period waits, its state is sent again this often (wall
  // s) so a controller that started late or lost the packet still gets it.
  // Paused, the newest state goes again with each status.
  static constexpr double kRepublishInterval = 0.25;
  static constexpr double kStatusInterval = 0.5;  // wall s, about 2 Hz
  // Realtime: a period later than this is not caught up with a burst.
  static constexpr double kMaxLag = 0.25;
  // Longest the node sleeps without a look (paused, waiting).
  static constexpr double kIdleInterval = 0.05;

  // Throws std::invalid_argument on bad options. Warnings (late
  // controllers, physics errors) go to `log`.
  SimNode(std::unique_ptr<Physics> physics, SimOptions options,
          std::ostream& log, WallTime now);

  // The first states and status.
  void Start(WallTime now, SimOutbox* out);
  // A decoded command received on `channel`: <prefix>_COMMAND_<robot>, or
  // <prefix>_COMMAND_loose with one target per loose servo
  // (Physics::loose_servo_count, in the loose state's joint order).
  void OnCommand(const joint_command_t& cmd, const std::string& channel,
                 WallTime now);
  // A decoded control request; acknowledged by a status in `out`.
  void OnControl(const sim_control_t& msg, WallTime now, SimOutbox* out);
  // A status heard on our <prefix>_SIM_STATUS: our own (looped back) is
  // ignored; another simulator's is warned of once per simulator, since
  // two on one URL and prefix take each other's commands and controls.
  void OnSimStatus(const sim_status_t& status);
  // The other simulators heard on our channels, by instance.
  const std::set<std::string>& other_simulators() const {
    return other_simulators_;
  }
  // A message on our channels that did not decode; `what` for last_error.
  void OnMalformed(const std::string& what);
  // Does what is due at `now` (at most one control period) and returns when
  // it wants to be called again (now: at once).
  WallTime Tick(WallTime now, SimOutbox* out);
  // Stops (SIGINT/SIGTERM): writes --checkpoint-on-exit, final status.
  void Stop(StopReason reason, WallTime now, SimOutbox* out);
  // Set once the node has stopped (QUIT, duration, Stop).
  const std::optional<StopReason>& stopped() const { return stopped_; }

  const Physics& physics() const { return *physics_; }
  const SimOptions& options() const { return options_; }
  int steps_per_period() const { return steps_per_period_; }
  double period() const { return period_; }  // s of sim time
  // Checkpoint files (sim_core/physics/checkpoint.h). Loading needs the
  // scenario that runs. Throw std::runtime_error naming the path.
  void SaveCheckpoint(const std::string& path) const;
  void LoadCheckpoint(const std::string& path);
  const std::string& exit_checkpoint_error() const {
    return exit_checkpoint_error_;
  }
  // State publications (one per control period and after reset/load;
  // re-sends, while waiting or paused, counted apart). Zero with
  // --no-state.
  int64_t states_published() const { return states_published_; }
  int64_t states_resent() const { return states_resent_; }

  sim_status_t status() const;
  // One line for the end of a run.
  std::string Summary() const;

 private:
  // Lockstep answers to one state, per robot.
  struct Answers {
    std::map<std::string, std::vector<bool>> answered;  // by controller
    std::vector<std::optional<joint_command_t>> command;
    std::vector<int> controller;  // index in --controllers of the command
  };
  struct Published {
    int64_t seq;
    std::vector<std::pair<std::string, SimOutbox::Message>> messages;
  };

  bool lockstep() const { return options_.clock == ClockMode::kLockstep; }
  // Lockstep: the seq whose answers the next period applies, or -1 when it
  // runs without (the first `actuation_delay` periods after a (re)start).
  int64_t AwaitedSeq() const;
  bool LockstepReady() const;
  std::string MissingControllers(int64_t seq) const;
  WallTime CheckLockstepWait(WallTime now, SimOutbox* out);
  void RunPeriod(WallTime now, SimOutbox* out);
  void PublishStates(WallTime now, SimOutbox* out);
  // The newest state of every robot (and the scene) under state_seq_.
  Published ReadStates() const;
  // Paused, with each status: what a viewer that joined late, or lost the
  // state that ended a STEP, needs (lockstep: the states still awaited).
  void ResendNewestStates(SimOutbox* out);
  // Lockstep: the states whose answers are still awaited, again.
  void ResendAwaitedStates(SimOutbox* out);
  void PublishStatus(WallTime now, SimOutbox* out);
  void Restarted(WallTime now, SimOutbox* out);
  void Reanchor(WallTime now);
  void ClearPending();
  void Fail(const std::string& error);
  void Finish(StopReason reason, WallTime now, SimOutbox* out);

  std::unique_ptr<Physics> physics_;
  SimOptions options_;
  std::ostream& log_;
  int steps_per_period_ = 1;
  double period_ = 0.01;
  CommandFilter filter_;
  std::optional<StopReason> stopped_;

  bool paused_ = false;
  bool quit_ = false;
  int64_t steps_pending_ = 0;  // control periods still to run after STEP
  int64_t state_seq_ = -1;     // seq of the newest state
  int64_t epoch_seq_ = 0;      // seq of the first state since start/reset
  int64_t status_seq_ = 0;
  int64_t steps_ = 0;
  int64_t states_published_ = 0;
  int64_t states_resent_ = 0;
  std::deque<Published> recent_;  // lockstep: states still awaited

  // Realtime and fast: the newest valid command per robot.
  std::vector<std::optional<joint_command_t>> pending_;
  // Lockstep: answers by state seq, and the robots each controller drives.
  std::map<int64_t, Answers> answers_;
  std::map<std::string, std::vector<bool>> controller_robots_;
  WallTime wait_start_;
  WallTime last_republish_;
  int timeout_warnings_ = 0;
  std::string waiting_for_;

  WallTime anchor_;  // realtime: period k starts at anchor + k*period/speed
  int64_t periods_since_anchor_ = 0;

  bool ran_period_ = false;
  WallTime first_period_wall_;
  WallTime end_wall_;
  double advanced_ = 0;  // s of sim time stepped (resets do not undo it)

  WallTime last_status_;
  double last_status_sim_time_ = 0;
  double real_time_factor_ = 0;
  int64_t commands_applied_ = 0;
  int64_t rejected_joint_count_ = 0;
  int64_t rejected_value_ = 0;
  int64_t rejected_robot_ = 0;
  int64_t rejected_seq_ = 0;
  int64_t rejected_sender_ = 0;
  // Senders refused for not being among --controllers (a few), named in
  // the lockstep wait warning: a misnamed controller otherwise looks like
  // a silent one.
  std::set<std::string> refused_senders_;
  int64_t repeated_commands_ = 0;  // CommandVerdict::kRepeat
  // Answers without targets: lockstep answers that move nothing, and
  // (kEmptyIgnored) the same outside lockstep.
  int64_t empty_answers_ = 0;
  int64_t malformed_ = 0;
  int64_t superseded_ = 0;
  int64_t control_gaps_ = 0;
  std::map<std::string, int64_t> control_last_seq_;
  int64_t control_seq_ = -1;
  std::string control_sender_;
  bool control_ok_ = true;
  std::string last_error_;
  std::string exit_checkpoint_error_;
  std::set<std::string> other_simulators_;
};

}  // namespace mrsim
