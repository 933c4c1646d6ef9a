// The frames waiting for one client, bounded: a client that reads slower
// than the simulation publishes gets the newest data, not an ever longer
// queue. When full, the oldest droppable frame (message data, time) makes
// room and is counted; a client whose undroppable frames alone (serverInfo,
// advertise, responses) overflow it is to be closed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include "foxglove/foxglove_bridge.h"

namespace mrsim::foxglove {

class ClientOutbox {
 public:
  explicit ClientOutbox(size_t max_frames = 256,
                        size_t max_bytes = 32 * 1024 * 1024)
      : max_frames_(max_frames), max_bytes_(max_bytes) {}

  // Queues `frame`, dropping the oldest droppable ones while over a bound.
  // False when it cannot be kept within the bounds: close the client.
  bool Push(Outgoing frame);
  std::optional<Outgoing> Pop();

  bool empty() const { return frames_.empty(); }
  size_t size() const { return frames_.size(); }
  size_t bytes() const { return bytes_; }
  int64_t dropped() const { return dropped_; }

 private:
  bool DropOldestDroppable();

  size_t max_frames_;
  size_t max_bytes_;
  std::deque<Outgoing> frames_;
  size_t bytes_ = 0;
  int64_t dropped_ = 0;
};

}  // namespace mrsim::foxglove
