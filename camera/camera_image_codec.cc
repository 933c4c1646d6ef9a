#include "camera/camera_image_codec.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "mrsim/wire_check.hpp"
#include "sim_core/codec/state_message.h"
#include "sim_core/scenario/scenario_schema.h"

namespace mrsim {
namespace {

void CheckSize(int width, int height) {
  if (width < 1 || width > kMaxCameraWidth || height < 1 ||
      height > kMaxCameraHeight) {
    throw std::invalid_argument(
        "camera_image_t.width/height: " + std::to_string(width) + "x" +
        std::to_string(height) + ", expected 1x1 to " +
        std::to_string(kMaxCameraWidth) + "x" +
        std::to_string(kMaxCameraHeight));
  }
}

// The size a JPEG's frame header (SOFn) declares, read before a pixel is
// allocated: a hostile header may claim 30000x30000 (3 GB) behind a
// message that says 16x16, and OpenCV would allocate it. False when the
// bytes are no JPEG (another format imdecode would take, a PNG, included)
// or no frame header comes before the scan.
bool JpegFrameSize(const std::vector<std::uint8_t>& d, int* width,
                   int* height) {
  if (d.size() < 4 || d[0] != 0xFF || d[1] != 0xD8) return false;
  size_t i = 2;
  while (i + 4 <= d.size()) {
    if (d[i] != 0xFF) return false;
    const std::uint8_t marker = d[i + 1];
    if (marker == 0xFF) {  // fill byte
      ++i;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {
      i += 2;  // markers without a length
      continue;
    }
    const size_t length = (static_cast<size_t>(d[i + 2]) << 8) | d[i + 3];
    if (length < 2) return false;
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 &&
                       marker != 0xC8 && marker != 0xCC;
    if (frame) {
      if (length < 7 || i + 9 > d.size()) return false;
      *height = (d[i + 5] << 8) | d[i + 6];
      *width = (d[i + 7] << 8) | d[i + 8];
      return true;
    }
    if (marker == 0xDA || marker == 0xD9) return false;  // scan, end
    i += 2 + length;
  }
  return false;
}

}  // namespace

camera_image_t EncodeCameraImage(const CameraImageHeader& header,
                                 const CameraPicture& picture,
                                 int jpeg_quality) {
  CheckSize(picture.width, picture.height);
  const size_t bytes = static_cast<size_t>(picture.width) * picture.height * 3;
  if (picture.rgb.size() != bytes) {
    throw std::invalid_argument(
        "camera picture: " + std::to_string(picture.rgb.size()) +
        " bytes for " + std::to_string(picture.width) + "x" +
        std::to_string(picture.height) + " RGB, expected " +
        std::to_string(bytes));
  }
  if (jpeg_quality < 0 || jpeg_quality > 100) {
    throw std::invalid_argument("JPEG quality " + std::to_string(jpeg_quality) +
                                ", expected 1..100 (0: raw RGB)");
  }
  camera_image_t msg;
  msg.utime = SimTimeToUtime(header.sim_time);
  msg.seq = header.seq;
  msg.robot = header.robot;
  msg.sender = header.sender;
  msg.camera = header.camera;
  msg.sensor_module = header.sensor_module;
  msg.name = header.name;
  msg.sim_time = header.sim_time;
  msg.width = picture.width;
  msg.height = picture.height;
  if (jpeg_quality == 0) {
    msg.encoding = kCameraEncodingRgb8;
    msg.data = picture.rgb;
  } else {
    msg.encoding = kCameraEncodingJpeg;
    const cv::Mat rgb(picture.height, picture.width, CV_8UC3,
                      const_cast<std::uint8_t*>(picture.rgb.data()));
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    cv::imencode(".jpg", bgr, msg.data,
                 {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
  }
  msg.num_bytes = static_cast<int32_t>(msg.data.size());
  return msg;
}

CameraPicture DecodeCameraImage(const camera_image_t& msg) {
  CheckSize(msg.width, msg.height);
  if (msg.num_bytes < 0 ||
      static_cast<size_t>(msg.num_bytes) != msg.data.size()) {
    throw std::invalid_argument(
        "camera_image_t.num_bytes: " + std::to_string(msg.num_bytes) + " for " +
        std::to_string(msg.data.size()) + " bytes");
  }
  CameraPicture picture;
  picture.width = msg.width;
  picture.height = msg.height;
  const size_t bytes = static_cast<size_t>(msg.width) * msg.height * 3;
  if (msg.encoding == kCameraEncodingRgb8) {
    if (msg.data.size() != bytes) {
      throw std::invalid_argument(
          "camera_image_t.data: " + std::to_string(msg.data.size()) +
          " bytes, expected width x height x 3 = " + std::to_string(bytes));
    }
    picture.rgb = msg.data;
    return picture;
  }
  if (msg.encoding != kCameraEncodingJpeg) {
    throw std::invalid_argument("camera_image_t.encoding: '" + msg.encoding +
                                "', expected rgb8 or jpeg");
  }
  int jpeg_width = 0, jpeg_height = 0;
  if (!JpegFrameSize(msg.data, &jpeg_width, &jpeg_height)) {
    throw std::invalid_argument("camera_image_t.data: not a JPEG picture");
  }
  if (jpeg_width != msg.width || jpeg_height != msg.height) {
    throw std::invalid_argument(
        "camera_image_t.data: a " + std::to_string(jpeg_width) + "x" +
        std::to_string(jpeg_height) + " JPEG, the message says " +
        std::to_string(msg.width) + "x" + std::to_string(msg.height));
  }
  cv::Mat bgr;
  try {
    // The declared size is bounded above; a JPEG claiming more than that
    // is refused before its pixels are allocated.
    bgr = cv::imdecode(msg.data, cv::IMREAD_COLOR);
  } catch (const cv::Exception&) {
    bgr.release();
  }
  if (bgr.empty()) {
    throw std::invalid_argument("camera_image_t.data: not a JPEG picture");
  }
  if (bgr.cols != msg.width || bgr.rows != msg.height) {
    throw std::invalid_argument(
        "camera_image_t.data: a " + std::to_string(bgr.cols) + "x" +
        std::to_string(bgr.rows) + " JPEG, the message says " +
        std::to_string(msg.width) + "x" + std::to_string(msg.height));
  }
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  picture.rgb.assign(rgb.data, rgb.data + bytes);
  return picture;
}

CameraImageHeader CameraImageHeaderOf(const camera_image_t& msg) {
  CameraImageHeader h;
  h.robot = msg.robot;
  h.sender = msg.sender;
  h.camera = msg.camera;
  h.sensor_module = msg.sensor_module;
  h.name = msg.name;
  h.seq = msg.seq;
  h.sim_time = msg.sim_time;
  return h;
}

}  // namespace mrsim
