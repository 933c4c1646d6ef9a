#include "lua_controller/process/lua_server.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/printable.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {
namespace {

// The node's lines, each line of a multi-line one (a Lua traceback) on its
// own, made printable: the script may come from someone else's file.
void WriteLog(const std::vector<std::string>& lines, std::ostream& log) {
  for (const std::string& text : lines) {
    size_t begin = 0;
    for (;;) {
      const size_t end = text.find('\n', begin);
      log << "mrsim-lua: "
          << Printable(std::string_view(text).substr(begin, end - begin))
          << "\n";
      if (end == std::string::npos) break;
      begin = end + 1;
    }
  }
}

}  // namespace

LuaServer::LuaServer(SignedLcm& lcm, LuaNodeOptions options, LuaNode node)
    : lcm_(lcm), node_(std::move(node)) {
  lcm::Subscription* state = lcm_.subscribe(
      StateChannel(options.prefix, options.robot), &LuaServer::OnState, this);
  lcm::Subscription* status = lcm_.subscribe(SimStatusChannel(options.prefix),
                                             &LuaServer::OnSimStatus, this);
  if (state == nullptr || status == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  state->setQueueCapacity(100);
  status->setQueueCapacity(100);
  subscriptions_ = {state, status};
  if (node_.takes_gait_commands()) {
    lcm::Subscription* gait =
        lcm_.subscribe(GaitChannel(options.prefix, options.robot),
                       &LuaServer::OnGaitCommand, this);
    if (gait == nullptr) {
      throw std::runtime_error("cannot subscribe to the LCM channels");
    }
    gait->setQueueCapacity(100);
    subscriptions_.push_back(gait);
  }
  if (options.cameras != 0) {
    lcm::Subscription* camera = lcm_.subscribe(
        ChannelName(ChannelNamed("camera"), options.prefix, options.robot),
        &LuaServer::OnCameraImage, this);
    lcm::Subscription* answers =
        lcm_.subscribe(CommandChannel(options.prefix, options.robot),
                       &LuaServer::OnCommand, this);
    if (camera == nullptr || answers == nullptr) {
      throw std::runtime_error("cannot subscribe to the LCM channels");
    }
    camera->setQueueCapacity(16);  // pictures are large
    answers->setQueueCapacity(100);
    subscriptions_.push_back(camera);
    subscriptions_.push_back(answers);
  }
}

LuaServer::~LuaServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

// LCM calls the handlers from C: nothing may escape them.
void LuaServer::OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    if (!DecodeMessage(rbuf, &state_)) {
      node_.OnMalformedState();
      return;
    }
    node_.OnState(state_, WallClock::now(), &outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
  } catch (...) {
    node_.OnMalformedState();
  }
}

// Foreign traffic on the simulator's channel is the simulator's to count.
void LuaServer::OnSimStatus(const lcm::ReceiveBuffer* rbuf,
                            const std::string&) {
  try {
    if (DecodeMessage(rbuf, &status_)) {
      node_.OnSimStatus(status_, WallClock::now());
    }
  } catch (...) {
  }
}

void LuaServer::OnGaitCommand(const lcm::ReceiveBuffer* rbuf,
                              const std::string&) {
  try {
    if (!DecodeMessage(rbuf, &command_)) {
      node_.OnMalformedGaitCommand();
      return;
    }
    node_.OnGaitCommand(command_, WallClock::now(), &outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
  } catch (...) {
    node_.OnMalformedGaitCommand();
  }
}

void LuaServer::OnCameraImage(const lcm::ReceiveBuffer* rbuf,
                              const std::string&) {
  try {
    if (!DecodeMessage(rbuf, &image_)) {
      node_.OnMalformedCameraImage();
      return;
    }
    node_.OnCameraImage(image_, WallClock::now(), &outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
  } catch (...) {
    node_.OnMalformedCameraImage();
  }
}

// Other controllers' commands are the simulator's to check and count.
void LuaServer::OnCommand(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    if (DecodeMessage(rbuf, &answer_)) {
      node_.OnCommand(answer_, WallClock::now(), &outbox_);
      PublishAll(lcm_, &outbox_, &buffer_);
    }
  } catch (...) {
  }
}

void LuaServer::Run(const std::function<bool()>& stop_requested,
                    std::ostream& log) {
  while (!stop_requested() && node_.error().empty() && !node_.done()) {
    const WallTime due = node_.Tick(WallClock::now(), &outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
    const double wait = SecondsBetween(WallClock::now(), due);
    HandleFor(lcm_,
              std::clamp(static_cast<int>(std::ceil(wait * 1e3)), 0, 100));
    WriteLog(node_.TakeLog(), log);
    log.flush();
  }
  WriteLog(node_.TakeLog(), log);
}

}  // namespace mrsim
