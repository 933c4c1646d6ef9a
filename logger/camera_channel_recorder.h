// Records one camera channel (<prefix>_CAMERA_<robot>, camera_image_t) as
// pictures instead of CSV rows: each of the robot's cameras gets a
// CameraPictureWriter folder, <stem>_<camera>/ (PNGs and index.csv). A
// message that does not decode, or whose picture the camera codec refuses,
// is counted and dropped like any malformed message. A picture carries
// the seq of the state it shows, and a camera pictures only every few
// states, so gaps are counted in pictures: a step in sim time of about n
// camera periods (the shortest step seen) means n - 1 pictures missing.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "logger/camera_picture_writer.h"
#include "logger/channel_ledger.h"
#include "mrsim/camera_image_t.hpp"

namespace mrsim {

class CameraChannelRecorder {
 public:
  // Cameras per channel (one robot's); pictures of higher numbers are
  // malformed, so forged numbers cannot make folders without end.
  static constexpr int kMaxCameras = 32;

  // Folders are created as pictures arrive: out_dir/<stem>_<camera>.
  CameraChannelRecorder(std::string out_dir, std::string stem);

  // One message as received (size bytes). Counts in `ledger`'s stats
  // (rows: pictures written; files: each camera's index.csv). Throws
  // std::runtime_error when a file cannot be written.
  void Record(const uint8_t* data, size_t size, ChannelLedger& ledger);
  // Puts every index's buffered lines on disk; throws naming the file.
  void Flush();

  // A camera's folder, "" when it has no picture.
  std::string Folder(int camera) const;

 private:
  struct Camera {
    std::unique_ptr<CameraPictureWriter> writer;
    bool have_last = false;
    int64_t last_seq = 0;
    double last_time = 0;
    uint64_t last_hash = 0;
    double period = 0;  // shortest step in sim time seen (0: none yet)
  };

  std::string out_dir_;
  std::string stem_;
  std::map<int, Camera> cameras_;
  camera_image_t msg_;  // reused
};

}  // namespace mrsim
