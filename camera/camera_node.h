// mrsim-camera's logic as a plain class: decoded robot and scene states and
// the wall time in, camera_image_t pictures (and, in lockstep, the answers
// to the states) out; CameraServer is the LCM adapter.
//
// The states of one control period (one seq, every robot of the scenario)
// are gathered first, so a picture shows every robot as it was at that
// seq. Camera k's frame j is due at sim time j / rate, decided from the
// states' sim time, never the wall clock, so which states are pictured is
// the same on every machine. Lockstep: every due state is pictured as it
// completes, then each robot imaged (every robot, when a camera on no
// robot is pictured) is answered with a joint_command_t
// without targets (the simulator waits for it and moves nothing with it).
// Realtime and fast: nothing is answered, so the simulator never waits;
// Flush pictures only the newest complete state, and a frame slot passed
// over without a picture counts as dropped.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera_frame_renderer.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/clock_mode.h"
#include "lcmtypes/runtime/outbox.h"
#include "lcmtypes/runtime/simulator_watch.h"
#include "mrsim/camera_image_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_status_t.hpp"

namespace mrsim {

using CameraOutbox = Outbox<camera_image_t, joint_command_t>;

inline constexpr char kDefaultCameraSender[] = "mrsim-camera";

// <prefix>_CAMERA_<owner>: camera_image_t of the cameras of `owner`, a
// robot's name, or "loose" (the loose sensor modules') or "scene" (the
// scene objects'): ScenarioCamera::owner.
inline std::string CameraChannel(const std::string& prefix,
                                 const std::string& owner) {
  static constexpr const ChannelSpec& kSpec = ChannelNamed("camera");
  return ChannelName(kSpec, prefix, owner);
}

struct CameraNodeOptions {
  std::string prefix = kDefaultChannelPrefix;
  // camera_image_t.sender and, in lockstep, joint_command_t.sender (what
  // mrsim-sim --controllers lists).
  std::string sender = kDefaultCameraSender;
  ClockMode clock = ClockMode::kRealtime;
  // Only this robot's cameras (or "loose"/"scene": those on no robot);
  // empty: every camera of the scenario.
  std::string robot;
  int jpeg_quality = 0;  // 0: rgb8; 1..100: JPEG of that quality
  bool exit_with_sim = false;
};

struct CameraNodeCounters {
  std::int64_t pictures = 0;   // camera_image_t published
  std::int64_t dropped = 0;    // frame slots passed over without a picture
  std::int64_t answers = 0;    // lockstep answers (re-sends included)
  std::int64_t states = 0;     // robot states accepted
  std::int64_t stale = 0;      // states older than one already taken
  std::int64_t malformed = 0;  // undecodable, foreign or unfit messages
};

class CameraNode {
 public:
  // Highest sim time taken (s): later ones are forged.
  static constexpr double kMaxSimTime = 1e9;

  // `renderer` must outlive the node. Throws std::invalid_argument when
  // options.robot is no robot of the scenario nor a camera owner, when
  // there is no camera to picture (lockstep would wait for nothing), or on
  // a JPEG quality outside 0..100.
  CameraNode(CameraNodeOptions options, CameraFrameRenderer* renderer,
             WallTime now);

  // StateChannel(prefix, robot) of every robot of the scenario, and
  // StateChannel(prefix, "loose") when it has loose parts.
  std::vector<std::string> StateChannels() const;
  const CameraNodeOptions& options() const { return options_; }
  // Indices in the renderer's cameras() of the cameras pictured.
  const std::vector<int>& imaged() const { return imaged_; }

  // A state received on `channel`. Lockstep: a completed period is
  // pictured and answered at once.
  void OnState(const std::string& channel, const robot_state_t& state,
               WallTime now, CameraOutbox* out);
  void OnScene(const scene_state_t& scene, WallTime now);
  // The loose parts' state (<prefix>_STATE_loose; OnState passes it on):
  // a period shows the newest one not after it.
  void OnLoose(const robot_state_t& loose, WallTime now);
  void OnSimStatus(const sim_status_t& status, WallTime now);
  // A message that did not decode; `what` names it (may be empty).
  void OnMalformed(const std::string& what);
  // Realtime and fast: pictures the newest complete period when a camera
  // is due (the adapter calls it once the messages waiting are handled).
  void Flush(CameraOutbox* out);
  // The simulator watch (warning, --exit-with-sim); returns when it wants
  // to be called again.
  WallTime Tick(WallTime now);

  bool done() const { return options_.exit_with_sim && watch_.stopped(); }
  bool gave_up() const { return watch_.gave_up(); }
  const CameraNodeCounters& counters() const { return counters_; }
  // The last malformed message's problem.
  const std::string& last_error() const { return last_error_; }
  std::vector<std::string> TakeLog();
  // "pictures published N, dropped N, malformed N, ..." for the exit line.
  std::string Summary() const;

 private:
  // The states of one control period.
  struct Period {
    std::int64_t seq = -1;
    double sim_time = 0;
    std::int64_t utime = 0;
    std::vector<std::optional<RobotState>> states;
    int count = 0;
    bool complete() const { return count == static_cast<int>(states.size()); }
  };

  void Malformed(std::string what);
  void Log(std::string line);
  void Picture(const Period& period, CameraOutbox* out);
  void Answer(const Period& period, CameraOutbox* out);

  CameraNodeOptions options_;
  CameraFrameRenderer* renderer_;
  std::map<std::string, int> channels_;  // state channel -> robot
  std::vector<int> imaged_;
  std::vector<bool> robot_imaged_;       // per robot: answered in lockstep
  std::vector<std::int64_t> next_slot_;  // per imaged camera
  double last_time_ = -1;                // sim time of the last period pictured

  Period gathering_;
  std::optional<Period> pending_;  // realtime/fast: complete, not pictured
  std::int64_t done_seq_ = -1;     // newest period completed
  // Lockstep: the answers to done_seq_, sent again with a re-sent state.
  std::vector<std::optional<joint_command_t>> answers_;
  std::int64_t answer_seq_ = 0;

  // Scene states by seq (the newest few): a period shows the newest scene
  // not after it.
  std::map<std::int64_t, std::vector<SceneObjectState>> scenes_;
  // The same for the loose parts' states; loose_channel_ is empty when
  // the scenario has no loose parts.
  std::string loose_channel_;
  std::map<std::int64_t, RobotState> looses_;

  SimulatorWatch watch_;
  CameraNodeCounters counters_;
  CameraPicture picture_;  // reused
  std::string last_error_;
  std::vector<std::string> log_;
};

}  // namespace mrsim
