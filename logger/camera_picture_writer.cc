#include "logger/camera_picture_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "logger/csv_format.h"

namespace mrsim {
namespace {

std::string MakeFolder(std::string folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder)) {
    throw std::runtime_error("cannot create picture folder " + folder + ": " +
                             (ec ? ec.message() : "not a directory"));
  }
  return folder;
}

// Whole file under a temporary name, then renamed: readers and a killed
// logger see no picture or a whole one. No fsync: like the CSVs, a logger
// crash loses nothing written, a power cut may (and 30 syncs a second per
// camera would slow the logger down on a disk).
void WriteWhole(const std::string& path, const std::vector<unsigned char>& b) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot write '" + path +
                             "': " + std::strerror(errno));
  }
  size_t done = 0;
  while (done < b.size()) {
    const ssize_t n = ::write(fd, b.data() + done, b.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = n < 0 ? errno : ENOSPC;
      ::close(fd);
      ::unlink(tmp.c_str());
      throw std::runtime_error("cannot write '" + path +
                               "': " + std::strerror(e));
    }
    done += static_cast<size_t>(n);
  }
  if (::close(fd) != 0 || ::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write '" + path +
                             "': " + std::strerror(e));
  }
}

}  // namespace

std::vector<unsigned char> EncodeCameraPng(const CameraPicture& picture) {
  const size_t bytes = static_cast<size_t>(picture.width) * picture.height * 3;
  if (picture.width < 1 || picture.height < 1 || picture.rgb.size() != bytes) {
    throw std::invalid_argument(
        "camera picture: " + std::to_string(picture.rgb.size()) +
        " bytes for " + std::to_string(picture.width) + "x" +
        std::to_string(picture.height) + " RGB");
  }
  const cv::Mat rgb(picture.height, picture.width, CV_8UC3,
                    const_cast<std::uint8_t*>(picture.rgb.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  std::vector<unsigned char> png;
  // Level 1: a few times faster than the default for pictures that are
  // about as small (rendered scenes have large flat areas).
  cv::imencode(".png", bgr, png, {cv::IMWRITE_PNG_COMPRESSION, 1});
  return png;
}

CameraPictureWriter::CameraPictureWriter(std::string folder)
    : folder_(MakeFolder(std::move(folder))), index_(folder_ + "/index.csv") {
  index_.WriteLine("seq,sim_time,file");
}

std::string CameraPictureWriter::Write(int64_t seq, double sim_time,
                                       const CameraPicture& picture) {
  char name[32];
  std::snprintf(name, sizeof(name), "%0*lld.png", kNameDigits,
                static_cast<long long>(pictures_));
  png_ = EncodeCameraPng(picture);
  WriteWhole(folder_ + "/" + name, png_);
  ++pictures_;
  std::string line;
  AppendInt(seq, &line);
  line.push_back(',');
  AppendDouble(sim_time, &line);
  line.push_back(',');
  line += name;
  index_.WriteLine(line);
  return name;
}

}  // namespace mrsim
