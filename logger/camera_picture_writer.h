// One robot camera's pictures on disk: a folder with a PNG per picture
// (000000.png, 000001.png, ... in the order written, so video tools read
// them as a sequence) and index.csv (seq, sim_time, file) saying which
// state each shows. A PNG is written beside its final name and renamed, so
// a killed logger never leaves a half picture under a .png name; the
// index is buffered like the CSV logger's rows (every line whole).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"
#include "logger/csv_writer.h"

namespace mrsim {

class CameraPictureWriter {
 public:
  // Digits of a picture's number in its file name (more past 999999).
  static constexpr int kNameDigits = 6;

  // Creates `folder` (and its index.csv). Throws std::runtime_error naming
  // the path when it cannot.
  explicit CameraPictureWriter(std::string folder);

  // Writes the picture as the next PNG and its index line; returns the
  // PNG's file name (within the folder). Throws std::runtime_error naming
  // the file.
  std::string Write(int64_t seq, double sim_time, const CameraPicture& picture);
  // Puts the buffered index lines on disk; throws like CsvWriter::Flush.
  void Flush() { index_.Flush(); }

  const std::string& folder() const { return folder_; }
  const std::string& index_path() const { return index_.path(); }
  int64_t pictures() const { return pictures_; }

 private:
  std::string folder_;
  CsvWriter index_;
  int64_t pictures_ = 0;
  std::vector<unsigned char> png_;  // reused
};

// The PNG of a picture (RGB, 8 bits, fast compression): the same bytes for
// the same picture.
std::vector<unsigned char> EncodeCameraPng(const CameraPicture& picture);

}  // namespace mrsim
