// Counts messages of one channel by their sequence number and finds gaps
// (lost messages) and jumps back (a restarted publisher, or reordering).
#pragma once

#include <cstdint>
#include <string>

namespace mrsim {

class SeqTracker {
 public:
  // What one new sequence number revealed.
  struct Event {
    int64_t missing = 0;  // messages skipped just before this one
    int64_t first_missing = 0;
    bool went_back = false;  // seq not above the previous one
    bool jumped = false;     // seq more than kMaxSeqGap ahead: no gap
    int64_t previous = 0;
  };

  Event Add(int64_t seq);

  int64_t count() const { return count_; }
  int64_t gaps() const { return gaps_; }
  int64_t missing() const { return missing_; }
  int64_t back_jumps() const { return back_jumps_; }
  int64_t forward_jumps() const { return forward_jumps_; }
  int64_t first() const { return first_; }
  int64_t last() const { return last_; }

 private:
  int64_t count_ = 0;
  int64_t gaps_ = 0;
  int64_t missing_ = 0;
  int64_t back_jumps_ = 0;
  int64_t forward_jumps_ = 0;
  int64_t first_ = 0;
  int64_t last_ = 0;
};

}  // namespace mrsim
