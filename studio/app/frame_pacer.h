// Paces the studio's frames while something live is shown: a steady rate
// (30 frames/s: what the live view needs, and on a machine without a GPU a
// software-rendered frame is most of a core, so drawing faster would take
// CPU from the simulator the studio watches).
#pragma once

#include <algorithm>
#include <chrono>

namespace mrsim::studio {

class FramePacer {
 public:
  using Clock = std::chrono::steady_clock;
  explicit FramePacer(double fps = 30) : period_(1.0 / fps) {}

  // Seconds to wait before the next frame (0: draw now); call once per
  // frame, before drawing it.
  double Wait(Clock::time_point now) {
    const double since = std::chrono::duration<double>(now - last_).count();
    if (since >= period_) {
      // Late (or first): draw now, the next one a period from here.
      last_ = now;
      return 0;
    }
    return std::max(0.0, period_ - since);
  }

 private:
  double period_;
  Clock::time_point last_{};
};

}  // namespace mrsim::studio
