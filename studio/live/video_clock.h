// How many frames a video recorded from the window needs now so that its
// length follows the wall clock: frame k shows the view at time k / fps
// after the start. A window that draws slower than the video's rate (a
// software renderer under load) repeats its last picture; one that draws
// faster skips pictures. So 3 s of recording always make 3 s of video.
#pragma once

#include <cstdint>

namespace mrsim::studio {

class VideoClock {
 public:
  // Throws std::invalid_argument for fps outside (0, 240].
  explicit VideoClock(double fps);

  // Frames to append for a picture drawn `elapsed_s` after the start (the
  // first call, at 0, gives 1). Never negative; a clock going back gives 0.
  int64_t FramesDue(double elapsed_s);
  int64_t frames() const { return frames_; }
  double fps() const { return fps_; }
  // The video's length so far.
  double seconds() const { return static_cast<double>(frames_) / fps_; }

 private:
  double fps_;
  int64_t frames_ = 0;
};

}  // namespace mrsim::studio
