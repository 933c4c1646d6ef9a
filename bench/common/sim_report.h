// What a finished mrsim-sim run reports about its own pace, for benchmarks
// that run it as a child with its output in a file.
#pragma once

#include <string>

namespace mrsim {

// The last "real-time factor X" in the file at `path`: sim seconds per wall
// second from the run's first period to its last, so startup (the model's
// compile, LCM's join) and the wait for a lockstep peer are left out.
// Throws std::runtime_error when the file holds none.
double ReadRealTimeFactor(const std::string& path);

}  // namespace mrsim
