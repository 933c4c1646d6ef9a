#include "viewer/process/state_inbox.h"

#include <cmath>
#include <exception>
#include <utility>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/codec/state_message.h"

namespace mrsim {

StateInbox::StateInbox(const StateViewer& viewer, const std::string& prefix,
                       FrameScheduler* scheduler)
    : viewer_(viewer), scheduler_(scheduler) {
  for (int r = 0; r < viewer.robot_count(); ++r) {
    channels_[StateChannel(prefix, viewer.robot_name(r))] = r;
  }
  gait_channel_ = GaitChannel(prefix, viewer.robot_name(viewer.follow_robot()));
  gait_status_channel_ =
      GaitStatusChannel(prefix, viewer.robot_name(viewer.follow_robot()));
  scene_channel_ = SceneChannel(prefix);
  status_channel_ = SimStatusChannel(prefix);
}

bool StateInbox::ReceiveStatus(const void* data, int size) {
  try {
    sim_status_t msg;
    if (size < 0 || !DecodeMessage(data, static_cast<size_t>(size), &msg)) {
      ++malformed_;
      last_error_ = status_channel_ + ": cannot decode sim_status_t";
      return false;
    }
    last_status_ = std::move(msg);
    ++statuses_;
    return true;
  } catch (const std::exception& e) {
    ++malformed_;
    last_error_ = status_channel_ + ": " + e.what();
  } catch (...) {
    ++malformed_;
  }
  return false;
}

bool StateInbox::ReceiveScene(const void* data, int size) {
  try {
    scene_state_t msg;
    if (size < 0 || !DecodeMessage(data, static_cast<size_t>(size), &msg)) {
      ++malformed_;
      last_error_ = scene_channel_ + ": cannot decode scene_state_t";
      return false;
    }
    if (msg.utime < 0 || !std::isfinite(msg.sim_time)) {
      ++malformed_;
      last_error_ = scene_channel_ + ": negative utime or non-finite time";
      return false;
    }
    std::vector<SceneObjectState> objects = FromSceneStateMessage(msg);
    const std::string problem = viewer_.CheckScene(objects);
    if (!problem.empty()) {
      ++malformed_;
      last_error_ = scene_channel_ + ": " + problem;
      return false;
    }
    if (!scheduler_->PushScene(msg.utime, std::move(objects))) {
      ++stale_;
      return false;
    }
    ++scenes_;
    return true;
  } catch (const std::exception& e) {
    ++malformed_;
    last_error_ = scene_channel_ + ": " + e.what();
  } catch (...) {
    ++malformed_;
    last_error_ = scene_channel_ + ": bad scene state";
  }
  return false;
}

bool StateInbox::ReceiveGait(const void* data, int size) {
  try {
    gait_command_t msg;
    if (size < 0 || !DecodeMessage(data, static_cast<size_t>(size), &msg)) {
      ++malformed_;
      last_error_ = gait_channel_ + ": cannot decode gait_command_t";
      return false;
    }
    if (have_gait_status_) return true;  // the status says what really runs
    if (!msg.gait.empty()) gait_ = msg.gait;
    if (!msg.motion.empty()) motion_ = msg.motion;
    gait_text_ = gait_;
    if (!motion_.empty()) {
      gait_text_ += gait_text_.empty() ? motion_ : " (" + motion_ + ")";
    }
    return true;
  } catch (...) {
    ++malformed_;
    last_error_ = gait_channel_ + ": bad gait command";
  }
  return false;
}

bool StateInbox::ReceiveGaitStatus(const void* data, int size) {
  try {
    gait_status_t msg;
    if (size < 0 || !DecodeMessage(data, static_cast<size_t>(size), &msg)) {
      ++malformed_;
      last_error_ = gait_status_channel_ + ": cannot decode gait_status_t";
      return false;
    }
    have_gait_status_ = true;
    gait_ = msg.gait;
    motion_ = msg.motion;
    gait_text_ = gait_ + " (" + motion_ + ")";
    return true;
  } catch (...) {
    ++malformed_;
    last_error_ = gait_status_channel_ + ": bad gait status";
  }
  return false;
}

std::vector<std::string> StateInbox::AllChannels() const {
  std::vector<std::string> all;
  for (const auto& [channel, robot] : channels_) all.push_back(channel);
  all.push_back(gait_channel_);
  all.push_back(gait_status_channel_);
  all.push_back(scene_channel_);
  all.push_back(status_channel_);
  return all;
}

bool StateInbox::Receive(const std::string& channel, const void* data,
                         int size) {
  try {
    if (channel == gait_status_channel_) return ReceiveGaitStatus(data, size);
    if (channel == gait_channel_) return ReceiveGait(data, size);
    if (channel == scene_channel_) return ReceiveScene(data, size);
    if (channel == status_channel_) return ReceiveStatus(data, size);
    const auto it = channels_.find(channel);
    if (it == channels_.end()) return false;
    const int robot = it->second;
    robot_state_t msg;
    if (size < 0 || !DecodeMessage(data, static_cast<size_t>(size), &msg)) {
      ++malformed_;
      last_error_ = channel + ": cannot decode robot_state_t";
      return false;
    }
    if (msg.robot != viewer_.robot_name(robot)) {
      ++malformed_;
      last_error_ = channel + ": state of robot '" + msg.robot + "'";
      return false;
    }
    RobotState state = FromRobotStateMessage(msg);
    const std::string problem = viewer_.Check(robot, state);
    if (!problem.empty()) {
      ++malformed_;
      last_error_ = channel + ": " + problem;
      return false;
    }
    if (msg.utime < 0) {
      ++malformed_;
      last_error_ = channel + ": negative utime";
      return false;
    }
    if (!scheduler_->Push(robot, msg.utime, std::move(state))) {
      ++stale_;
      return false;
    }
    ++accepted_;
    return true;
  } catch (const std::exception& e) {
    ++malformed_;
    last_error_ = channel + ": " + e.what();
  } catch (...) {
    ++malformed_;
    last_error_ = channel + ": unknown error";
  }
  return false;
}

}  // namespace mrsim
