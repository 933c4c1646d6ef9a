// camera_image_t from any bytes, as every reader of pictures decodes them
// (the logger, Python, the studio): the checked message decode, then
// DecodeCameraImage (JPEG included). A picture comes out whole and of the
// size the message says, or std::invalid_argument does. The first byte
// picks the input: 0, a whole encoded message; otherwise the rest is the
// data of a JPEG message whose size is bytes 1..2 (width) and 3..4
// (height), so the fuzzer reaches the JPEG decoder without building a
// message around it.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "camera/camera_image_codec.h"
#include "lcmtypes/runtime/decode.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  mrsim::camera_image_t msg;
  if (data[0] == 0) {
    if (!mrsim::DecodeMessage(data + 1, size - 1, &msg)) return 0;
  } else {
    if (size < 5) return 0;
    msg.width = (data[1] << 8) | data[2];
    msg.height = (data[3] << 8) | data[4];
    msg.encoding = mrsim::kCameraEncodingJpeg;
    msg.data.assign(data + 5, data + size);
    msg.num_bytes = static_cast<int32_t>(msg.data.size());
  }
  try {
    const mrsim::CameraPicture picture = mrsim::DecodeCameraImage(msg);
    if (picture.width != msg.width || picture.height != msg.height ||
        picture.rgb.size() != static_cast<size_t>(msg.width) * msg.height * 3) {
      std::abort();
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
