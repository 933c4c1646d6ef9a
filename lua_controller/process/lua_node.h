// mrsim-lua's logic as a plain state machine: answers each state of one
// robot with the joint targets of the user's Lua script (the state's sim
// time is the script's t, so a lockstep run is the same every time), the
// way GaitNode answers with a gait. Decoded messages and the wall time in,
// joint commands out; LuaServer is the LCM adapter. A script error stops
// the node (error() names the script line): every later step would fail
// the same way. Pictures of the robot's cameras (camera_image_t) reach
// the script as state.cameras; in lockstep the node waits, before it
// answers a state, for the camera process's answer to that state, so the
// script sees the same pictures on every run (docs/lua.md, "Cameras").
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/gait_status_timing.h"
#include "lcmtypes/runtime/outbox.h"
#include "lcmtypes/runtime/simulator_watch.h"
#include "lcmtypes/runtime/state_pacer.h"
#include "lua_controller/lua_script.h"
#include "mrsim/camera_image_t.hpp"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/scenario/scenario.h"

namespace mrsim {

using LuaOutbox = Outbox<joint_command_t, gait_status_t>;

struct LuaNodeOptions {
  std::string robot;
  std::string prefix = kDefaultChannelPrefix;
  std::string sender;  // joint_command_t.sender
  // Hz of sim time: states closer together than 1/rate are not answered
  // (0: every state). As in mrsim-gait, a skipped state the simulator
  // sends again (lockstep) makes the node answer every state.
  double rate = 100.0;
  bool exit_with_sim = false;
  // The robot's cameras, as the scenario (--scenario) gives them: -1
  // unknown (pictures are taken as they come; in lockstep the node waits
  // for the camera process only once it has heard it), 0 none (no picture
  // is read; state.cameras is empty).
  int cameras = -1;
  // The sender of the camera process's answers (mrsim-camera).
  std::string camera_sender = "mrsim-camera";
};

struct LuaNodeCounters {
  int64_t states_answered = 0;
  int64_t states_repeated = 0;
  int64_t states_skipped = 0;
  int64_t states_foreign = 0;
  int64_t messages_malformed = 0;
  int64_t commands_applied = 0;   // gait commands the script took
  int64_t commands_rejected = 0;  // refused by the script, or malformed
  int64_t pictures_received = 0;
  int64_t pictures_malformed = 0;  // refused by the camera codec
  int64_t states_waited = 0;       // held for the camera's answer
  int64_t camera_timeouts = 0;     // answered without it (kCameraWait)
};

class LuaNode {
 public:
  static constexpr double kSimulatorSilence = SimulatorWatch::kSimulatorSilence;
  static constexpr double kMaxSimTime = 1e9;  // s; later states are forged
  // Between gait statuses (a script with on_gait_command only): what tells
  // the studio and mrsim-ctl it takes steering.
  static constexpr double kHeartbeatInterval = kGaitStatusInterval;
  // Wall seconds a state waits for the camera process's answer before it
  // is answered without (then the node waits no more until it hears the
  // camera again): a missing camera process slows, never stops, a run.
  static constexpr double kCameraWait = 2.0;
  // Pictures kept per camera to pick from (the newest up to a state).
  static constexpr size_t kPicturesKept = 8;
  // States held at once; one more answers the oldest without waiting.
  static constexpr size_t kMaxWaiting = 16;
  // Camera numbers above are malformed (forged numbers cannot grow memory).
  static constexpr int kMaxCameras = 32;

  // `script` is already loaded (its syntax checked). axes_for(joint_count)
  // gives the hinge axes once the first state says how many joints there
  // are (may throw std::invalid_argument: the node fails). Throws
  // std::invalid_argument on a bad rate.
  LuaNode(LuaNodeOptions options, std::unique_ptr<LuaScript> script,
          std::function<std::vector<Axis>(int)> axes_for, WallTime now);

  void OnState(const robot_state_t& state, WallTime now, LuaOutbox* out);
  void OnMalformedState() { ++counters_.messages_malformed; }
  // A picture of one of the robot's cameras (others' are ignored); one the
  // camera codec refuses is counted and dropped.
  void OnCameraImage(const camera_image_t& image, WallTime now, LuaOutbox* out);
  void OnMalformedCameraImage() { ++counters_.pictures_malformed; }
  // A command on the robot's command channel: the camera process's answer
  // to a state says its pictures of that state were all sent.
  void OnCommand(const joint_command_t& command, WallTime now, LuaOutbox* out);
  void OnSimStatus(const sim_status_t& status, WallTime now);
  // A steering request, for a script that defines on_gait_command
  // (takes_gait_commands): the script's verdict is acknowledged in a
  // gait_status_t on <prefix>_GAIT_STATUS_<robot>, as mrsim-gait does.
  void OnGaitCommand(const gait_command_t& command, WallTime now,
                     LuaOutbox* out);
  void OnMalformedGaitCommand() { ++counters_.messages_malformed; }
  bool takes_gait_commands() const { return script_->takes_gait_commands(); }
  // Warnings, the gait status heartbeat (takes_gait_commands only) and,
  // with exit_with_sim, a silent simulator; returns when it wants to be
  // called again.
  WallTime Tick(WallTime now, LuaOutbox* out);

  bool done() const { return options_.exit_with_sim && watch_.stopped(); }
  bool gave_up() const { return watch_.gave_up(); }
  // Set when the script failed (with its line) or the axes do not fit.
  const std::string& error() const { return error_; }
  std::vector<std::string> TakeLog();
  const LuaNodeCounters& counters() const { return counters_; }
  std::string Summary() const;

 private:
  void Process(const robot_state_t& state, LuaOutbox* out);
  void HandleState(const robot_state_t& state, LuaOutbox* out);
  bool WaitsForCamera(int64_t seq) const;
  void ReleaseWaiting(WallTime now, LuaOutbox* out, bool make_room = false);
  void FillCameras(int64_t seq);
  void PublishStatus(WallTime now, LuaOutbox* out);
  void Log(std::string line);

  LuaNodeOptions options_;
  std::unique_ptr<LuaScript> script_;
  std::function<std::vector<Axis>(int)> axes_for_;
  std::optional<std::vector<std::string>> axes_;  // set by the first state
  LuaRobotState input_;                           // reused each step

  StatePacer pacer_;
  SimulatorWatch watch_;

  LuaNodeCounters counters_;
  gait_status_t status_{};  // what the gait status says (steering scripts)
  WallTime next_heartbeat_;
  std::vector<std::string> log_;
  std::string error_;

  // Cameras: the pictures kept (oldest first) of each camera number.
  std::vector<std::deque<LuaRobotState::Camera>> pictures_;
  int64_t camera_answered_ = -1;  // newest state the camera process answered
  bool camera_heard_ = false;
  bool camera_silent_ = false;  // timed out, not heard since
  struct Waiting {
    robot_state_t state;
    WallTime since;
  };
  std::deque<Waiting> waiting_;
  int64_t last_processed_seq_ = -1;
};

}  // namespace mrsim
