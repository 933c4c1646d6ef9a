#include "studio/live/video_clock.h"

#include <cmath>
#include <stdexcept>

namespace mrsim::studio {

VideoClock::VideoClock(double fps) : fps_(fps) {
  if (!(fps > 0 && fps <= 240)) {
    throw std::invalid_argument("video rate must be in (0, 240] frames/s");
  }
}

int64_t VideoClock::FramesDue(double elapsed_s) {
  if (!(elapsed_s >= 0)) elapsed_s = 0;
  // Frames 0 .. floor(elapsed * fps) show a picture at or before now.
  const int64_t wanted = static_cast<int64_t>(std::floor(elapsed_s * fps_)) + 1;
  if (wanted <= frames_) return 0;
  const int64_t due = wanted - frames_;
  frames_ = wanted;
  return due;
}

}  // namespace mrsim::studio
