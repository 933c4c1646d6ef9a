#include "viewer/frame_writer.h"

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <system_error>

namespace mrsim {

std::unique_ptr<FrameWriter> FrameWriter::Video(const std::string& path,
                                                double fps, int width,
                                                int height) {
  auto w = std::make_unique<FrameWriter>(Key());
  w->path_ = path;
  w->width_ = width;
  w->height_ = height;
  const std::filesystem::path parent =
      std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent)) {
    throw std::runtime_error(path + ": folder " + parent.string() +
                             " does not exist");
  }
  // H.264 plays in browsers; MPEG-4 Part 2 only in desktop players, but
  // every FFmpeg build can write it.
  for (const char* codec : {"avc1", "mp4v"}) {
    if (w->video_.open(
            path, cv::CAP_FFMPEG,
            cv::VideoWriter::fourcc(codec[0], codec[1], codec[2], codec[3]),
            fps, cv::Size(width, height), true)) {
      w->codec_ = codec;
      return w;
    }
  }
  throw std::runtime_error(path +
                           ": cannot open for writing as MP4 (avc1 or "
                           "mp4v); is the folder writable and OpenCV built "
                           "with FFmpeg?");
}

std::unique_ptr<FrameWriter> FrameWriter::Pngs(const std::string& dir) {
  auto w = std::make_unique<FrameWriter>(Key());
  w->path_ = dir;
  w->codec_ = "png";
  w->png_ = true;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw std::runtime_error(dir + ": cannot create the frames folder" +
                             (ec ? " (" + ec.message() + ")" : ""));
  }
  return w;
}

FrameWriter::~FrameWriter() { Close(); }

std::string FrameWriter::PngName(const std::string& dir, int64_t index) {
  char name[64];
  std::snprintf(name, sizeof(name), "frame_%06lld.png",
                static_cast<long long>(index));
  return (std::filesystem::path(dir) / name).string();
}

void FrameWriter::Write(const cv::Mat& bgr, int64_t index) {
  if (closed_) throw std::runtime_error(path_ + ": write after close");
  if (png_) {
    const std::string file = PngName(path_, index);
    bool ok = false;
    try {
      ok = cv::imwrite(file, bgr);
    } catch (const cv::Exception& e) {
      throw std::runtime_error(file + ": " + e.what());
    }
    if (!ok) throw std::runtime_error(file + ": cannot write the PNG");
  } else {
    if (bgr.cols != width_ || bgr.rows != height_ || bgr.type() != CV_8UC3) {
      throw std::runtime_error(path_ + ": frame of the wrong size or type");
    }
    video_.write(bgr);
  }
  ++frames_;
}

void FrameWriter::Close() {
  if (closed_) return;
  closed_ = true;
  if (!png_) video_.release();
}

}  // namespace mrsim
