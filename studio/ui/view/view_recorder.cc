#include "studio/ui/view/view_recorder.h"

#include <GL/gl.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <system_error>

namespace mrsim::studio {

ViewRecorder::ViewRecorder() = default;
ViewRecorder::~ViewRecorder() { Stop(); }

void ViewRecorder::Start(const std::string& path) {
  if (recording()) throw std::runtime_error("a video is being recorded");
  path_ = path;
  writer_.reset();
  clock_.emplace(kFps);
  width_ = height_ = 0;
}

const std::string& ViewRecorder::path() const {
  static const std::string kNone;
  return path_ ? *path_ : kNone;
}

void ViewRecorder::Capture(const mjrRect& view) {
  if (!recording() || view.width < 16 || view.height < 16) return;
  const auto now = std::chrono::steady_clock::now();
  if (!writer_) {
    // H.264 wants even sizes; the first picture fixes the video's.
    width_ = view.width & ~1;
    height_ = view.height & ~1;
    try {
      writer_ = FrameWriter::Video(*path_, kFps, width_, height_);
    } catch (const std::exception&) {
      path_.reset();
      clock_.reset();
      throw;
    }
    start_ = now;
  }
  const int64_t due =
      clock_->FramesDue(std::chrono::duration<double>(now - start_).count());
  if (due == 0) return;
  rgb_.resize(static_cast<size_t>(view.width) * view.height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(view.left, view.bottom, view.width, view.height, GL_RGB,
               GL_UNSIGNED_BYTE, rgb_.data());
  const cv::Mat image(view.height, view.width, CV_8UC3, rgb_.data());
  cv::Mat flipped, bgr;
  cv::flip(image, flipped, 0);  // OpenGL's rows go up
  cv::cvtColor(flipped, bgr, cv::COLOR_RGB2BGR);
  if (bgr.cols != width_ || bgr.rows != height_) {
    // The window changed size while recording: the video keeps its own.
    cv::Mat sized;
    cv::resize(bgr, sized, cv::Size(width_, height_));
    bgr = sized;
  }
  try {
    for (int64_t i = 0; i < due; ++i) {
      writer_->Write(bgr, writer_->frames_written());
    }
  } catch (const std::exception&) {
    Stop();
    throw;
  }
}

std::optional<RecordedVideo> ViewRecorder::Stop() {
  if (!recording()) return std::nullopt;
  RecordedVideo video;
  video.path = *path_;
  if (writer_) {
    writer_->Close();
    video.codec = writer_->codec();
    video.seconds = static_cast<double>(writer_->frames_written()) / kFps;
  }
  writer_.reset();
  path_.reset();
  clock_.reset();
  std::error_code ec;
  video.bytes = std::filesystem::file_size(video.path, ec);
  if (ec) return std::nullopt;  // never opened: no picture was drawn
  videos_.push_back(video);
  return video;
}

std::string NextVideoPath(const std::string& folder, const std::string& stem) {
  const std::filesystem::path dir = folder.empty() ? "." : folder;
  for (int n = 1;; ++n) {
    const std::filesystem::path p =
        dir / (stem + "-video-" + std::to_string(n) + ".mp4");
    if (!std::filesystem::exists(p)) return p.string();
  }
}

std::string DescribeVideo(const RecordedVideo& video) {
  char text[64];
  const double mb = static_cast<double>(video.bytes) / 1e6;
  if (mb >= 0.1) {
    std::snprintf(text, sizeof(text), "%.1f s, %.1f MB", video.seconds, mb);
  } else {
    std::snprintf(text, sizeof(text), "%.1f s, %.0f kB", video.seconds,
                  static_cast<double>(video.bytes) / 1e3);
  }
  return text;
}

}  // namespace mrsim::studio
