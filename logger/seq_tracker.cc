#include "logger/seq_tracker.h"

#include "lcmtypes/runtime/seq_gap.h"

namespace mrsim {

SeqTracker::Event SeqTracker::Add(int64_t seq) {
  Event e;
  if (count_ == 0) {
    first_ = seq;
  } else if (seq > last_) {
    // Overflow-safe; a jump too far to be lost messages (a restart, a
    // forged number) is no gap.
    e.missing = SeqGap(last_, seq);
    if (e.missing > 0) {
      e.first_missing = last_ + 1;
      ++gaps_;
      missing_ += e.missing;
    } else if (seq - 1 != last_) {
      e.jumped = true;
      e.previous = last_;
      ++forward_jumps_;
    }
  } else {
    e.went_back = true;
    e.previous = last_;
    ++back_jumps_;
  }
  last_ = seq;
  ++count_;
  return e;
}

}  // namespace mrsim
