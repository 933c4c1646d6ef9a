#include "foxglove/camera_image_json.h"

#include <nlohmann/json.hpp>
#include <string>

#include "camera/camera_image_codec.h"
#include "foxglove/foxglove_schemas.h"
#include "mrsim/message_json.hpp"

namespace mrsim::foxglove {
namespace {

bool IsJpeg(const camera_image_t& msg) {
  return msg.encoding == kCameraEncodingJpeg;
}

void WriteTimestamp(uint64_t ns, JsonWriter& out) {
  out.Raw(R"("timestamp":{"sec":)");
  out.Int(static_cast<int64_t>(ns / 1'000'000'000));
  out.Raw(R"(,"nsec":)");
  out.Int(static_cast<int64_t>(ns % 1'000'000'000));
  out.Raw("}");
}

std::string_view BytesOf(const camera_image_t& msg) {
  return {reinterpret_cast<const char*>(msg.data.data()), msg.data.size()};
}

}  // namespace

const char* FoxgloveImageSchemaName(const camera_image_t& msg) {
  return IsJpeg(msg) ? "foxglove.CompressedImage" : "foxglove.RawImage";
}

const char* FoxgloveImageSchema(const camera_image_t& msg) {
  return IsJpeg(msg) ? kCompressedImageSchema : kRawImageSchema;
}

void WriteFoxgloveImageJson(const camera_image_t& msg, uint64_t timestamp_ns,
                            JsonWriter& out) {
  out.Raw("{");
  WriteTimestamp(timestamp_ns, out);
  out.Raw(R"(,"frame_id":)");
  out.String(msg.name);
  if (IsJpeg(msg)) {
    out.Raw(R"(,"format":"jpeg","data":)");
  } else {
    out.Raw(R"(,"width":)");
    out.Int(msg.width);
    out.Raw(R"(,"height":)");
    out.Int(msg.height);
    out.Raw(R"(,"encoding":"rgb8","step":)");
    out.Int(static_cast<int64_t>(msg.width) * 3);
    out.Raw(R"(,"data":)");
  }
  WriteBase64String(BytesOf(msg), out);
  out.Raw("}");
}

void WriteCameraImageWithoutBytes(const camera_image_t& msg, JsonWriter& out) {
  camera_image_t header;
  header.utime = msg.utime;
  header.seq = msg.seq;
  header.robot = msg.robot;
  header.sender = msg.sender;
  header.camera = msg.camera;
  header.sensor_module = msg.sensor_module;
  header.name = msg.name;
  header.sim_time = msg.sim_time;
  header.width = msg.width;
  header.height = msg.height;
  header.encoding = msg.encoding;
  header.num_bytes = msg.num_bytes;
  WriteJson(header, out);
}

const char* CameraImageWithoutBytesSchema() {
  // Built once from the generated schema, so the other fields follow the
  // .lcm file.
  static const std::string schema = [] {
    const MessageJsonType* type =
        FindMessageJsonType(camera_image_t::getHash());
    nlohmann::json s = nlohmann::json::parse(type->schema);
    s["properties"]["data"] = {
        {"type", "array"},
        {"maxItems", 0},
        {"description",
         "always empty on mrsim-foxglove: the picture is on "
         "/camera/<robot>/<camera> as foxglove.RawImage (rgb8) or "
         "foxglove.CompressedImage (jpeg)"}};
    return s.dump();
  }();
  return schema.c_str();
}

void WriteBase64String(std::string_view bytes, JsonWriter& out) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4 + 2);
  text.push_back('"');
  size_t i = 0;
  const auto byte = [&bytes](size_t k) {
    return static_cast<uint32_t>(static_cast<unsigned char>(bytes[k]));
  };
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    for (int shift = 18; shift >= 0; shift -= 6) {
      text.push_back(kAlphabet[(v >> shift) & 63]);
    }
  }
  const size_t rest = bytes.size() - i;
  if (rest > 0) {
    const uint32_t v = byte(i) << 16 | (rest == 2 ? byte(i + 1) << 8 : 0u);
    text.push_back(kAlphabet[(v >> 18) & 63]);
    text.push_back(kAlphabet[(v >> 12) & 63]);
    text.push_back(rest == 2 ? kAlphabet[(v >> 6) & 63] : '=');
    text.push_back('=');
  }
  text.push_back('"');
  out.Raw(text);
}

}  // namespace mrsim::foxglove
