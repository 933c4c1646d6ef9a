#include "logger/seq_tracker.h"

namespace mrsim {

SeqTracker::Event SeqTracker::Add(int64_t seq) {
  Event e;
  if (count_ == 0) {
    first_ = seq;
  } else if (seq > last_ + 1) {
    e.missing = seq - last_ - 1;
    e.first_missing = last_ + 1;
    ++gaps_;
    missing_ += e.missing;
  } else if (seq <= last_) {
    e.went_back = true;
    e.previous = last_;
    ++back_jumps_;
  }
  last_ = seq;
  ++count_;
  return e;
}

}  // namespace mrsim
