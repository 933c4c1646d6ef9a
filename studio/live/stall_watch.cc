#include "studio/live/stall_watch.h"

#include <algorithm>

namespace mrsim::studio {

void StallWatch::Start(long count, WallTime now) {
  started_ = true;
  count_ = count;
  last_ = now;
  longest_ = 0;
}

void StallWatch::Update(long count, WallTime now) {
  if (!started_) Start(count, now);
  if (count <= count_) return;
  // Several generations at once (read from a checkpoint, or polled late)
  // share the time between: each took at most that long.
  longest_ = std::max(longest_, SecondsBetween(last_, now) / (count - count_));
  count_ = count;
  last_ = now;
}

double StallWatch::Bound() const {
  return std::max(min_s_, factor_ * longest_);
}

std::optional<double> StallWatch::Stalled(WallTime now) const {
  if (!started_) return std::nullopt;
  const double silent = SecondsBetween(last_, now);
  if (silent <= Bound()) return std::nullopt;
  return silent;
}

}  // namespace mrsim::studio
