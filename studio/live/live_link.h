// The studio's one LCM connection: hears every channel of a prefix for a
// LiveSession and publishes what it asks. Polled from the window's frame
// loop (no thread), so the session is only touched by the UI thread.
#pragma once

#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"
#include "studio/live/live_session.h"

namespace mrsim::studio {

class LiveLink {
 public:
  // Throws std::runtime_error naming the URL when LCM cannot open it.
  // With a key in `auth`, signs what it publishes and hands the session
  // only messages signed with it (refused ones are counted, not shown).
  LiveLink(const std::string& url, LiveSession* session, AuthConfig auth = {});
  ~LiveLink();
  LiveLink(const LiveLink&) = delete;
  LiveLink& operator=(const LiveLink&) = delete;

  // Hands everything that arrived to the session, waiting up to
  // timeout_ms for the first message; returns how many.
  int Poll(int timeout_ms);
  // Publishes and empties `out`.
  void Publish(StudioOutbox* out);
  const std::string& url() const { return url_; }

 private:
  void OnRaw(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

  std::string url_;
  LiveSession* session_;
  SignedLcm lcm_;
  lcm::Subscription* subscription_ = nullptr;
  std::vector<uint8_t> buffer_;
};

}  // namespace mrsim::studio
