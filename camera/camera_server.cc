#include "camera/camera_server.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>

#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {

CameraServer::CameraServer(SignedLcm& lcm, CameraNode& node)
    : lcm_(lcm), node_(node) {
  const std::string& prefix = node_.options().prefix;
  for (const std::string& channel : node_.StateChannels()) {
    subscriptions_.push_back(
        lcm_.subscribe(channel, &CameraServer::OnState, this));
  }
  subscriptions_.push_back(
      lcm_.subscribe(SceneChannel(prefix), &CameraServer::OnScene, this));
  subscriptions_.push_back(lcm_.subscribe(SimStatusChannel(prefix),
                                          &CameraServer::OnSimStatus, this));
  for (lcm::Subscription* s : subscriptions_) {
    if (s == nullptr) {
      throw std::runtime_error("cannot subscribe to the LCM channels");
    }
    s->setQueueCapacity(100);
  }
}

CameraServer::~CameraServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

// LCM calls the handlers from C: nothing may escape them.
void CameraServer::OnState(const lcm::ReceiveBuffer* rbuf,
                           const std::string& channel) {
  try {
    robot_state_t state;
    if (!DecodeMessage(rbuf, &state)) {
      node_.OnMalformed(channel + ": cannot decode robot_state_t");
      return;
    }
    node_.OnState(channel, state, WallClock::now(), &outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
  } catch (const std::exception& e) {
    outbox_.clear();
    node_.OnMalformed(channel + ": " + e.what());
  } catch (...) {
    outbox_.clear();
    node_.OnMalformed(channel);
  }
}

void CameraServer::OnScene(const lcm::ReceiveBuffer* rbuf,
                           const std::string& channel) {
  try {
    scene_state_t scene;
    if (!DecodeMessage(rbuf, &scene)) {
      node_.OnMalformed(channel + ": cannot decode scene_state_t");
      return;
    }
    node_.OnScene(scene, WallClock::now());
  } catch (...) {
    node_.OnMalformed(channel);
  }
}

// Foreign traffic on the simulator's channel is the simulator's to count.
void CameraServer::OnSimStatus(const lcm::ReceiveBuffer* rbuf,
                               const std::string&) {
  try {
    sim_status_t status;
    if (DecodeMessage(rbuf, &status))
      node_.OnSimStatus(status, WallClock::now());
  } catch (...) {
  }
}

void CameraServer::Run(const std::function<bool()>& stop_requested,
                       std::ostream& log) {
  auto write_log = [&] {
    for (const std::string& line : node_.TakeLog()) {
      log << "mrsim-camera: " << line << "\n";
    }
    log.flush();
  };
  while (!stop_requested() && !node_.done()) {
    const WallTime due = node_.Tick(WallClock::now());
    const double wait = SecondsBetween(WallClock::now(), due);
    // Every message waiting is handled before a picture is taken, so a
    // slow picture never makes the next one older than it must be.
    HandleFor(lcm_,
              std::clamp(static_cast<int>(std::ceil(wait * 1e3)), 0, 100));
    // (A bounded number of times: a fast simulator never stops sending.)
    for (int i = 0; i < 100 && HandleFor(lcm_, 0) > 0; ++i) {
    }
    node_.Flush(&outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
    write_log();
  }
  write_log();
}

}  // namespace mrsim
