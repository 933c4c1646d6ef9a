// Writes rendered frames to an MP4 file (OpenCV through FFmpeg: H.264
// "avc1", which browsers play, or MPEG-4 Part 2 "mp4v" when no H.264
// encoder is available) or
// to numbered PNG files frame_<k>.png in a folder, k being the frame's index
// in simulation time (frame time = k / fps).
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>

namespace mrsim {

class FrameWriter {
 public:
  // MP4 at `path`: throws std::runtime_error naming the path if it cannot be
  // opened. The file is complete (playable) after Close() or destruction.
  static std::unique_ptr<FrameWriter> Video(const std::string& path, double fps,
                                            int width, int height);
  // PNG frames in `dir` (created if missing): throws std::runtime_error
  // naming the folder if it cannot be created or written.
  static std::unique_ptr<FrameWriter> Pngs(const std::string& dir);

  // Use Video() or Pngs(); the key keeps the constructor theirs.
  struct Key {
   private:
    Key() {}  // user-provided: no aggregate init from outside
    friend class FrameWriter;
  };
  explicit FrameWriter(Key) {}
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Appends a BGR frame (CV_8UC3 of the opened size). Throws
  // std::runtime_error naming the file on a write failure.
  void Write(const cv::Mat& bgr, int64_t index);
  // Finishes the file; later Writes are errors. Safe to call twice.
  void Close();

  int64_t frames_written() const { return frames_; }
  // "avc1" or "mp4v" for a video, "png" for frames.
  const std::string& codec() const { return codec_; }
  const std::string& path() const { return path_; }
  // Path of the PNG for frame `index` (PNG mode).
  static std::string PngName(const std::string& dir, int64_t index);

 private:
  std::string path_;
  std::string codec_;
  bool png_ = false;
  cv::VideoWriter video_;
  int width_ = 0;
  int height_ = 0;
  int64_t frames_ = 0;
  bool closed_ = false;
};

}  // namespace mrsim
