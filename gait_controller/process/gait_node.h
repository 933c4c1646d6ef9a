// mrsim-gait's logic as a plain state machine: answers each state of one
// robot with joint targets from a GaitController (the state's sim time is
// the clock, so a lockstep run equals RunGait in process), takes gait
// commands from LCM or the keyboard, and reports what it runs in a
// gait_status_t (on change and about once a second). Decoded messages and
// the wall time in, messages to publish out; GaitServer is the LCM adapter.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/gait_controller.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/clock_mode.h"
#include "lcmtypes/runtime/gait_status_timing.h"
#include "lcmtypes/runtime/outbox.h"
#include "lcmtypes/runtime/simulator_watch.h"
#include "lcmtypes/runtime/state_pacer.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"

namespace mrsim {

using GaitOutbox = Outbox<joint_command_t, gait_status_t>;

// Where mrsim-gait keeps its state beside a simulator checkpoint:
// "<checkpoint>.gait-<robot>".
std::string GaitCheckpointPath(const std::string& checkpoint,
                               const std::string& robot);

struct GaitNodeOptions {
  std::string robot;
  std::string prefix = kDefaultChannelPrefix;
  std::string sender;  // joint_command_t.sender
  // Hz of sim time: states closer together than 1/rate are not answered
  // (0: answer every state). If the simulator sends a skipped state again
  // (lockstep waiting for it), the node answers it and every state after.
  double rate = 100.0;
  // Stop (done()) once the simulator says it is stopping: a batch run's
  // controller ends with it.
  bool exit_with_sim = false;
  GaitControllerOptions controller;
};

struct GaitNodeCounters {
  int64_t states_answered = 0;
  int64_t states_repeated = 0;  // a recent seq again: its answer re-sent
  int64_t states_skipped = 0;   // closer than 1/rate, or older than the last
  int64_t states_foreign = 0;   // another robot's
  int64_t messages_malformed = 0;
  int64_t commands_applied = 0;
  int64_t commands_rejected = 0;
};

class GaitNode {
 public:
  static constexpr double kHeartbeatInterval = kGaitStatusInterval;
  static constexpr double kNoSimulatorWarning =
      SimulatorWatch::kNoSimulatorWarning;
  static constexpr double kSimulatorSilence = SimulatorWatch::kSimulatorSilence;
  static constexpr double kNoSimulatorGiveUp =
      SimulatorWatch::kNoSimulatorGiveUp;
  static constexpr double kMaxSimTime = 1e9;  // s; later states are forged

  // axes_for(joint_count) gives the hinge axes once the first state says
  // how many joints there are; it may throw std::invalid_argument, which
  // makes the node fail (see error()). Throws std::invalid_argument on a
  // bad rate.
  GaitNode(GaitNodeOptions options,
           std::function<std::vector<Axis>(int)> axes_for, Gait initial,
           WallTime now);

  // The first gait status: mrsim-ctl waits for it before sending.
  void Start(WallTime now, GaitOutbox* out);
  // A decoded state on STATE_<robot>.
  void OnState(const robot_state_t& state, WallTime now, GaitOutbox* out);
  // A decoded gait command on GAIT_<robot>; commands for another robot are
  // rejected.
  void OnGaitCommand(const gait_command_t& command, WallTime now,
                     GaitOutbox* out);
  // Applies a gait command from any source (LCM, keyboard) all or nothing;
  // before the first state it is queued. Never throws: a bad command is
  // counted, logged and acknowledged as rejected.
  void Apply(const gait_command_t& command, const std::string& source,
             WallTime now, GaitOutbox* out);
  // Something on our channels that does not decode.
  void OnMalformedState();
  void OnMalformedGait(WallTime now, GaitOutbox* out);
  // Checkpoints: a SAVE_CHECKPOINT request the simulator acknowledges as
  // done makes the node write, to GaitCheckpointPath(path), its state from
  // just before it answered the saved state; an acknowledged
  // LOAD_CHECKPOINT restores that file, so the gait continues as it did
  // after the save (bit for bit in lockstep). Requests and statuses from
  // <prefix>_SIM_CONTROL and <prefix>_SIM_STATUS.
  void OnSimControl(const sim_control_t& request);
  void OnSimStatus(const sim_status_t& status, WallTime now, GaitOutbox* out);
  // With exit_with_sim: the simulator stopped (or went silent for
  // kSimulatorSilence), so should this node.
  bool done() const { return options_.exit_with_sim && watch_.stopped(); }
  // done() because no simulator was heard within kNoSimulatorGiveUp: the
  // run did not happen (mrsim-gait exits 1).
  bool gave_up() const { return watch_.gave_up(); }
  // mrsim-gait --resume CHECKPOINT: restores the state saved beside that
  // checkpoint when the first state comes. Throws std::runtime_error
  // naming the file when it cannot be read.
  void Resume(const std::string& checkpoint);

  // The heartbeat; returns when it wants to be called again.
  WallTime Tick(WallTime now, GaitOutbox* out);

  // Lines to print (changes, rejections, warnings) since the last call.
  std::vector<std::string> TakeLog();
  // Set when the node cannot go on (the joint axes do not fit the robot).
  const std::string& error() const { return error_; }
  const GaitNodeCounters& counters() const { return counters_; }
  // Null until the first state arrived.
  const GaitController* controller() const { return controller_.get(); }
  std::string Describe() const;
  gait_status_t status() const;
  // One line for the end of a run.
  std::string Summary() const;

 private:
  struct Snapshot {
    GaitController controller;
    bool have_last = false;
    double last_time = 0;
  };
  void HandleState(const robot_state_t& state, GaitOutbox* out);
  // Hands the sensor readings to a CPG gait with feedback.
  void FeedSensors(const robot_state_t& state);
  void WriteCheckpoint(const std::string& path, double sim_time) const;
  void Restore(const std::string& path);
  void Acknowledge(const gait_command_t& command, int8_t result,
                   const std::string& error);
  void PublishStatus(WallTime now, GaitOutbox* out);
  void CheckFit();
  void Log(std::string line);

  GaitNodeOptions options_;
  std::function<std::vector<Axis>(int)> axes_for_;
  Gait initial_;
  std::unique_ptr<GaitController> controller_;
  std::deque<std::pair<gait_command_t, std::string>> queued_;

  StatePacer pacer_;
  SimulatorWatch watch_;
  bool warned_other_name_ = false;
  // The controller just before answering the state of each sim time.
  std::map<double, Snapshot> snapshots_;
  std::map<std::pair<std::string, int64_t>, sim_control_t> requests_;
  std::string resume_path_;  // restore when the controller is built
  WallTime last_status_;
  int64_t status_seq_ = 0;
  int64_t ack_seq_ = -1;
  std::string ack_sender_;
  int8_t ack_result_ = gait_status_t::NONE;
  std::string ack_error_;
  std::string warning_;

  GaitNodeCounters counters_;
  std::vector<std::string> log_;
  std::string error_;
};

}  // namespace mrsim
