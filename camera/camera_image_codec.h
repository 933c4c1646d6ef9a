// Pictures <-> camera_image_t: one encoder for mrsim-camera and one checked
// decoder for every reader (the logger, Python's Node and log readers, the
// studio). A decoded message is hostile until this says otherwise: its
// sizes must agree with its bytes and stay within the camera limits, and a
// JPEG must decode to the size it claims.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsim/camera_image_t.hpp"

namespace mrsim {

// The encodings camera_image_t carries.
inline constexpr char kCameraEncodingRgb8[] = "rgb8";
inline constexpr char kCameraEncodingJpeg[] = "jpeg";

// An RGB picture: height x width x 3 bytes, red first, top row first.
struct CameraPicture {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

// What a picture shows and where it comes from (every field of the message
// but the pixels).
struct CameraImageHeader {
  std::string robot;
  std::string sender;
  int camera = 0;
  int sensor_module = 0;
  std::string name;
  std::int64_t seq = 0;
  double sim_time = 0.0;
};

// The message for `picture`: raw (jpeg_quality 0) or a JPEG of that
// quality (1..100). Throws std::invalid_argument when the picture's size
// is outside the camera limits (scenario_schema.h) or its bytes disagree
// with it.
camera_image_t EncodeCameraImage(const CameraImageHeader& header,
                                 const CameraPicture& picture,
                                 int jpeg_quality = 0);

// The picture a decoded message carries. Throws std::invalid_argument
// naming the field that is wrong: a size outside the camera limits, bytes
// that disagree with width x height x 3, an unknown encoding, a JPEG that
// does not decode or decodes to another size.
CameraPicture DecodeCameraImage(const camera_image_t& msg);

// The header fields of a message.
CameraImageHeader CameraImageHeaderOf(const camera_image_t& msg);

}  // namespace mrsim
