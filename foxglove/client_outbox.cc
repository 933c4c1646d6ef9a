#include "foxglove/client_outbox.h"

#include <utility>

namespace mrsim::foxglove {

bool ClientOutbox::DropOldestDroppable() {
  for (auto it = frames_.begin(); it != frames_.end(); ++it) {
    if (!it->droppable) continue;
    bytes_ -= it->data.size();
    frames_.erase(it);
    ++dropped_;
    return true;
  }
  return false;
}

bool ClientOutbox::Push(Outgoing frame) {
  if (frame.data.size() > max_bytes_) {
    if (frame.droppable) {
      ++dropped_;
      return true;
    }
    return false;
  }
  while (frames_.size() + 1 > max_frames_ ||
         bytes_ + frame.data.size() > max_bytes_) {
    if (!DropOldestDroppable()) {
      if (frame.droppable) {
        ++dropped_;
        return true;
      }
      return false;
    }
  }
  bytes_ += frame.data.size();
  frames_.push_back(std::move(frame));
  return true;
}

std::optional<Outgoing> ClientOutbox::Pop() {
  if (frames_.empty()) return std::nullopt;
  Outgoing frame = std::move(frames_.front());
  frames_.pop_front();
  bytes_ -= frame.data.size();
  return frame;
}

}  // namespace mrsim::foxglove
