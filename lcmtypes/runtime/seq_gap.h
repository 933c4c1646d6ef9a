// How many messages a sender's sequence number says were lost, safely: a
// received seq can be anything (a forged INT64_MAX, a restarted sender), and
// seq - last - 1 on such numbers overflows, which is undefined behaviour
// and turned counters into garbage.
#pragma once

#include <cstdint>

namespace mrsim {

// Gaps wider than this are not lost messages (a sender that lost a million
// in a row is not sending): a restart or a forged number.
inline constexpr int64_t kMaxSeqGap = 1000000;

// Messages between `last` and `seq` (seq - last - 1) when seq is ahead of
// last by 2 .. kMaxSeqGap + 1; otherwise 0. Never overflows.
inline int64_t SeqGap(int64_t last, int64_t seq) {
  if (seq <= last) return 0;
  const uint64_t ahead =
      static_cast<uint64_t>(seq) - static_cast<uint64_t>(last);
  return ahead - 1 <= static_cast<uint64_t>(kMaxSeqGap)
             ? static_cast<int64_t>(ahead - 1)
             : 0;
}

// True when seq is more than `distance` behind last. Never overflows.
inline bool SeqFarBehind(int64_t last, int64_t seq, int64_t distance) {
  return seq<last&& static_cast<uint64_t>(last) -
             static_cast<uint64_t>(seq)> static_cast<uint64_t>(distance);
}

}  // namespace mrsim
