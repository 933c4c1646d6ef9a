// Time helpers shared by the processes: wall-clock stamps for LCM messages
// and durations of the monotonic clock in seconds.
#pragma once

#include <chrono>
#include <cstdint>

namespace mrsim {

// Microseconds since the Unix epoch (the utime of LCM messages that are not
// stamped with simulation time).
inline std::int64_t WallMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// A duration in seconds as a double.
template <typename Rep, typename Period>
double Seconds(std::chrono::duration<Rep, Period> d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace mrsim
