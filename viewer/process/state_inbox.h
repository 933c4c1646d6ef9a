// Decodes robot_state_t messages (live or from a log) for the robots of the
// scenario, and scene_state_t for its movable scene objects, and feeds the
// frame scheduler; also follows the gait commands of
// the followed robot for the overlay. Malformed or foreign messages are
// counted and dropped, never trusted; nothing here throws.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mrsim/sim_status_t.hpp"
#include "viewer/frame_scheduler.h"
#include "viewer/state_viewer.h"

namespace mrsim {

class StateInbox {
 public:
  // Channels are StateChannel(prefix, robot) for every robot of `viewer`,
  // and GaitChannel(prefix, followed robot).
  StateInbox(const StateViewer& viewer, const std::string& prefix,
             FrameScheduler* scheduler);

  const std::map<std::string, int>& channels() const { return channels_; }
  const std::string& gait_channel() const { return gait_channel_; }
  // GaitStatusChannel(prefix, followed robot): what mrsim-gait really runs
  // (keyboard steering included); preferred to the gait commands.
  const std::string& gait_status_channel() const {
    return gait_status_channel_;
  }
  // SceneChannel(prefix): scene_state_t.
  const std::string& scene_channel() const { return scene_channel_; }
  // SimStatusChannel(prefix): whether the simulator is stopping, for
  // --exit-with-sim.
  const std::string& status_channel() const { return status_channel_; }
  // Every channel Receive takes: what a live viewer subscribes to.
  std::vector<std::string> AllChannels() const;
  // "gait (motion)" from the latest gait status (or, until one came, the
  // latest gait commands); empty before any.
  const std::string& gait_text() const { return gait_text_; }
  // One message; returns true when it reached the scheduler.
  bool Receive(const std::string& channel, const void* data, int size);
  bool ReceiveGait(const void* data, int size);
  bool ReceiveGaitStatus(const void* data, int size);
  bool ReceiveScene(const void* data, int size);
  bool ReceiveStatus(const void* data, int size);

  int64_t accepted() const { return accepted_; }
  int64_t scenes() const { return scenes_; }  // scene states accepted
  // Simulator statuses decoded, and the newest of them.
  int64_t statuses() const { return statuses_; }
  const std::optional<sim_status_t>& last_status() const {
    return last_status_;
  }
  int64_t malformed() const { return malformed_; }
  int64_t stale() const { return stale_; }
  const std::string& last_error() const { return last_error_; }

 private:
  const StateViewer& viewer_;
  FrameScheduler* scheduler_;
  std::map<std::string, int> channels_;
  std::string gait_channel_;
  std::string gait_status_channel_;
  bool have_gait_status_ = false;
  std::string scene_channel_;
  std::string status_channel_;
  std::optional<sim_status_t> last_status_;
  int64_t statuses_ = 0;
  std::string gait_;
  std::string motion_;
  std::string gait_text_;
  int64_t accepted_ = 0;
  int64_t scenes_ = 0;
  int64_t malformed_ = 0;
  int64_t stale_ = 0;
  std::string last_error_;
};

}  // namespace mrsim
