// The studio as an LCM node (issue "studio part 2"): what it hears from a
// running simulation (robots, their states, scene, simulator and gait
// status, live plots) and the requests it sends (simulator controls,
// steering), with acknowledgements matched on sender and seq. A plain core:
// decoded channel bytes and `now` in, messages to publish out; LiveLink owns
// the socket and the clock, and tests drive this class with a fake clock.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lcmtypes/runtime/gait_status_timing.h"
#include "lcmtypes/runtime/outbox.h"
#include "logger/lcm_type_registry.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "studio/live/plot_series.h"

namespace mrsim::studio {

using StudioOutbox = Outbox<sim_control_t, gait_command_t>;

struct LiveSessionOptions {
  std::string prefix = "MRSIM";
  // This window's sender name (one per process; seq counts from 1).
  std::string sender = "mrsim-studio";
  // A request with no acknowledgement after this long has failed.
  double request_timeout_s = 3.0;
  // A robot not heard from for this long is listed as silent.
  double robot_silent_s = 2.0;
  // A robot heard this long without a gait status has no controller that
  // takes steering (gait_status_timing.h).
  double gait_status_wait_s = kGaitStatusWait;
};

// Whether steering a robot (gait_command_t) will be answered. A controller
// declares that it takes steering by what it publishes: a gait status on
// <prefix>_GAIT_STATUS_<robot> (mrsim-gait does, about once a second; a
// program of one's own may); one that does not (mrsim-lua, most programs)
// never sends one, and steering it would go unanswered.
struct Steering {
  enum class State {
    kAnswered,    // its controller's gait status is being heard
    kUnknown,     // too early to tell (robot not heard yet, or just now)
    kUnanswered,  // nothing steers it: steering is refused before sending
  };
  State state = State::kUnknown;
  std::string why;  // for kUnknown and kUnanswered, in words
};

// One request the studio sent and what became of it.
struct LiveRequest {
  enum class Kind { kSim, kGait };
  enum class State { kPending, kDone, kRefused, kNoAnswer };
  Kind kind = Kind::kSim;
  int64_t seq = 0;
  std::string what;  // "pause", "step 10", "motion forward 1", ...
  State state = State::kPending;
  std::string error;  // why refused, or "no answer within 3 s"
  WallTime sent;
};

// What the studio knows of one robot.
struct LiveRobot {
  std::string name;
  robot_state_t state;   // the newest
  int64_t states = 0;    // received
  WallTime first_heard;  // its first state or gait status
  WallTime last_heard;
  bool silent = false;
  std::optional<gait_status_t> gait;  // the newest, once mrsim-gait spoke
  WallTime gait_heard;                // when `gait` came
};

class LiveSession {
 public:
  explicit LiveSession(LiveSessionOptions options);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  // One message as it came off the wire. Channels outside the prefix, and
  // those the studio does not read (commands, the farm's), are ignored;
  // bytes that are not the channel's type are counted and dropped. Never
  // throws.
  void OnMessage(const std::string& channel, const uint8_t* data, size_t size,
                 WallTime now);
  // Expires requests without an answer and marks silent robots.
  void Tick(WallTime now);

  // Simulator controls (sim_control_t on <prefix>_SIM_CONTROL); each
  // returns the request's seq.
  int64_t Pause(WallTime now, StudioOutbox* out);
  int64_t Resume(WallTime now, StudioOutbox* out);
  int64_t Step(int periods, WallTime now, StudioOutbox* out);
  int64_t Reset(WallTime now, StudioOutbox* out);
  int64_t SetSpeed(double speed, WallTime now, StudioOutbox* out);
  int64_t SaveCheckpoint(const std::string& path, WallTime now,
                         StudioOutbox* out);
  int64_t LoadCheckpoint(const std::string& path, WallTime now,
                         StudioOutbox* out);
  // Releases (attached=false, DETACH) or re-makes (ATTACH) the lock named
  // `lock` (as robot_state_t lists it) of `robot`. Throws
  // std::invalid_argument for an empty robot or lock name.
  int64_t SetLockAttached(const std::string& robot, const std::string& lock,
                          bool attached, WallTime now, StudioOutbox* out);
  // Whether steering `robot` will be answered, and why not (Steering).
  Steering SteeringOf(const std::string& robot, WallTime now) const;
  // Steering (gait_command_t on <prefix>_GAIT_<robot>): a motion with its
  // strength in [-1, 1], the seven gait parameters, or a gait by name.
  // Throws std::invalid_argument for an unknown motion or a value out of
  // range, and std::runtime_error (SteeringOf's why) for a robot nothing
  // steers, before anything is sent.
  int64_t Steer(const std::string& robot, const std::string& motion,
                double strength, WallTime now, StudioOutbox* out);
  int64_t SetGaitParameters(const std::string& robot,
                            const std::vector<double>& parameters, WallTime now,
                            StudioOutbox* out);
  int64_t SetGait(const std::string& robot, const std::string& gait,
                  WallTime now, StudioOutbox* out);

  // Robots heard, in name order (not the loose parts: loose()).
  std::vector<const LiveRobot*> robots() const;
  // The loose parts' newest state (<prefix>_STATE_loose), when heard.
  const std::optional<robot_state_t>& loose() const { return loose_; }
  const LiveRobot* robot(const std::string& name) const;
  const std::optional<sim_status_t>& sim_status() const { return status_; }
  const std::optional<scene_state_t>& scene() const { return scene_; }
  const std::vector<LiveRequest>& requests() const { return requests_; }
  const LiveRequest* request(int64_t seq) const;

  // Live plots: any numeric column of any channel heard, named as mrsim-log
  // names its CSV columns (`sensor_module0.force`, `module3.joint.angle`).
  // Plotting starts with the next message on that channel.
  PlotSeries& AddPlot(const std::string& channel, const std::string& column,
                      double window_s = 10.0);
  void RemovePlot(size_t index);
  const std::vector<std::unique_ptr<PlotSeries>>& plots() const {
    return plots_;
  }
  // The numeric columns the last message of `channel` had, without its
  // time and sequence number (empty if none).
  std::vector<std::string> Columns(const std::string& channel) const;
  // Channels heard with a known type, in name order.
  std::vector<std::string> Channels() const;

  const std::string& prefix() const { return options_.prefix; }
  int64_t messages() const { return messages_; }
  int64_t malformed() const { return malformed_; }
  // Messages on a channel of ours whose type is not the one it carries.
  int64_t foreign() const { return foreign_; }
  const std::string& last_error() const { return last_error_; }

 private:
  struct ChannelReader;

  int64_t SendSim(sim_control_t msg, const std::string& what, WallTime now,
                  StudioOutbox* out);
  int64_t SendGait(gait_command_t msg, const std::string& what, WallTime now,
                   StudioOutbox* out);
  void OnSimStatus(const sim_status_t& msg);
  void OnGaitStatus(const gait_status_t& msg, WallTime now);
  void Feed(ChannelReader& reader, const std::string& channel,
            const uint8_t* data, size_t size);
  ChannelReader* Reader(const std::string& channel, const uint8_t* data,
                        size_t size);
  void Drop(const std::string& channel, const std::string& why, bool foreign);

  LiveSessionOptions options_;
  LcmTypeRegistry registry_;
  std::map<std::string, LiveRobot> robots_;
  std::optional<sim_status_t> status_;
  std::optional<scene_state_t> scene_;
  std::optional<robot_state_t> loose_;
  std::vector<LiveRequest> requests_;
  int64_t next_seq_ = 1;
  std::map<std::string, std::unique_ptr<ChannelReader>> readers_;
  std::vector<std::unique_ptr<PlotSeries>> plots_;
  int64_t messages_ = 0;
  int64_t malformed_ = 0;
  int64_t foreign_ = 0;
  std::string last_error_;
};

}  // namespace mrsim::studio
