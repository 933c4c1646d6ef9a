// Records the studio's 3-D view to an MP4 (H.264 through OpenCV and
// FFmpeg, viewer/frame_writer.h), as MuJoCo's simulate does: Start and
// Stop from the window, the pixels of the view read after it is drawn and
// before the panels go over it. The video's length follows the wall clock
// (VideoClock), and every video made this session is listed with its size.
#pragma once

#include <mujoco/mujoco.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "studio/live/video_clock.h"
#include "viewer/frame_writer.h"

namespace mrsim::studio {

// A finished video.
struct RecordedVideo {
  std::string path;
  std::uintmax_t bytes = 0;
  double seconds = 0;
  std::string codec;  // "avc1" (H.264) or "mp4v"
};

class ViewRecorder {
 public:
  static constexpr double kFps = 30;

  ViewRecorder();
  ~ViewRecorder();

  // Starts a video at `path` (its folder must exist). The first Capture
  // fixes its size. Throws std::runtime_error when already recording.
  void Start(const std::string& path);
  // After the 3-D view is drawn into the bound framebuffer: appends its
  // pixels (OpenGL, bottom-left origin rect) as the frames now due. Throws
  // std::runtime_error naming the file when it cannot be written (the
  // recording then stops).
  void Capture(const mjrRect& view);
  // Finishes the file and returns it; nothing when not recording.
  std::optional<RecordedVideo> Stop();

  bool recording() const { return path_.has_value(); }
  // Length of the video being recorded, s.
  double seconds() const { return clock_ ? clock_->seconds() : 0; }
  const std::string& path() const;
  const std::vector<RecordedVideo>& videos() const { return videos_; }

 private:
  std::optional<std::string> path_;
  std::unique_ptr<FrameWriter> writer_;
  std::optional<VideoClock> clock_;
  std::chrono::steady_clock::time_point start_;
  int width_ = 0;
  int height_ = 0;
  std::vector<unsigned char> rgb_;
  std::vector<RecordedVideo> videos_;
};

// The first free "<folder>/<stem>-video-<n>.mp4", n from 1.
std::string NextVideoPath(const std::string& folder, const std::string& stem);

// "3.0 s, 1.2 MB" for a list or a note.
std::string DescribeVideo(const RecordedVideo& video);

}  // namespace mrsim::studio
