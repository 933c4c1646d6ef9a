#include "studio/live/live_link.h"

#include <stdexcept>

#include "common/lcm_url.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim::studio {

LiveLink::LiveLink(const std::string& url, LiveSession* session,
                   AuthConfig auth)
    : url_(url), session_(session), lcm_(url, std::move(auth)) {
  if (!lcm_.good()) {
    throw std::runtime_error(CannotOpenLcm(url));
  }
  // Every channel: the session picks what it reads, counts what it cannot.
  subscription_ = lcm_.subscribe(".*", &LiveLink::OnRaw, this);
  // A slow frame must drop old messages, not block the simulator.
  subscription_->setQueueCapacity(1000);
}

LiveLink::~LiveLink() {
  if (subscription_ != nullptr) lcm_.unsubscribe(subscription_);
}

void LiveLink::OnRaw(const lcm::ReceiveBuffer* rbuf,
                     const std::string& channel) {
  session_->OnMessage(channel, static_cast<const uint8_t*>(rbuf->data),
                      rbuf->data_size, WallClock::now());
}

int LiveLink::Poll(int timeout_ms) {
  const int handled = HandleFor(lcm_, timeout_ms);
  session_->Tick(WallClock::now());
  return handled;
}

void LiveLink::Publish(StudioOutbox* out) { PublishAll(lcm_, out, &buffer_); }

}  // namespace mrsim::studio
