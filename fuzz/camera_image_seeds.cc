// Writes the camera_image target's seed corpus: real pictures as
// mrsim-camera sends them (raw and JPEG, as whole messages and as bare
// JPEG data) and a JPEG whose header claims a huge frame. Run by hand when
// the message or the codec changes:
//   cmake --build build --target mrsim_fuzz_camera_seeds
//   build/fuzz/mrsim_fuzz_camera_seeds fuzz/corpus/camera_image
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"

namespace {

void Write(const std::string& path, char mode,
           const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.put(mode);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

void WriteMessage(const std::string& path, const mrsim::camera_image_t& msg) {
  std::vector<std::uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  Write(path, 0, bytes);
}

// Mode 1: width and height (2 bytes each), then the JPEG bytes.
void WriteJpeg(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& jpeg) {
  std::vector<std::uint8_t> bytes = {static_cast<std::uint8_t>(width >> 8),
                                     static_cast<std::uint8_t>(width & 0xff),
                                     static_cast<std::uint8_t>(height >> 8),
                                     static_cast<std::uint8_t>(height & 0xff)};
  bytes.insert(bytes.end(), jpeg.begin(), jpeg.end());
  Write(path, 1, bytes);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mrsim_fuzz_camera_seeds CORPUS_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  mrsim::CameraImageHeader header;
  header.robot = "eye";
  header.sender = "mrsim-camera";
  header.name = "eye/sm0/camera";
  header.seq = 42;
  header.sim_time = 0.42;
  mrsim::CameraPicture picture{16, 12, {}};
  for (int y = 0; y < 12; ++y) {
    for (int x = 0; x < 16; ++x) {
      picture.rgb.push_back(static_cast<std::uint8_t>(x * 16));
      picture.rgb.push_back(static_cast<std::uint8_t>(y * 20));
      picture.rgb.push_back(static_cast<std::uint8_t>((x + y) * 8));
    }
  }
  WriteMessage(dir + "/rgb8_16x12", mrsim::EncodeCameraImage(header, picture));
  const mrsim::camera_image_t jpeg =
      mrsim::EncodeCameraImage(header, picture, 75);
  WriteMessage(dir + "/jpeg_16x12", jpeg);
  WriteJpeg(dir + "/bare_jpeg_16x12", 16, 12, jpeg.data);
  // The same JPEG with its frame header saying 30000x30000: refused before
  // a pixel is allocated.
  std::vector<std::uint8_t> huge = jpeg.data;
  for (size_t i = 2; i + 9 <= huge.size(); ++i) {
    if (huge[i] == 0xFF && huge[i + 1] == 0xC0) {
      huge[i + 5] = huge[i + 7] = 30000 >> 8;
      huge[i + 6] = huge[i + 8] = 30000 & 0xff;
      break;
    }
  }
  WriteJpeg(dir + "/huge_frame_header", 16, 12, huge);
  WriteJpeg(dir + "/huge_frame_header_said", 30000, 30000, huge);
  return 0;
}
