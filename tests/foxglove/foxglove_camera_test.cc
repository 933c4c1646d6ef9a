// Camera pictures in Foxglove: FoxgloveBridge driven in-process with
// camera_image_t messages, as mrsim-camera publishes them.
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"
#include "foxglove/camera_image_json.h"
#include "foxglove/client_outbox.h"
#include "foxglove/foxglove_bridge.h"

namespace mrsim::foxglove {
namespace {

using Json = nlohmann::json;

BridgeOutput Lcm(FoxgloveBridge& bridge, const std::string& channel,
                 const camera_image_t& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return bridge.OnLcm(channel, buf.data(), buf.size(), 0);
}

// The channels advertised to `client`, by topic.
std::vector<Json> Advertised(const BridgeOutput& out, ClientId client) {
  std::vector<Json> channels;
  for (const Outgoing& o : out.send) {
    if (o.client != client || o.binary) continue;
    const Json text = Json::parse(o.data);
    if (text["op"] != "advertise") continue;
    for (const Json& c : text["channels"]) channels.push_back(c);
  }
  return channels;
}

// The payloads of the message data frames to `client`.
std::vector<Json> PayloadsTo(const BridgeOutput& out, ClientId client) {
  std::vector<Json> payloads;
  for (const Outgoing& o : out.send) {
    if (o.client != client || !o.binary || o.data[0] != 0x01) continue;
    payloads.push_back(Json::parse(o.data.substr(13)));
  }
  return payloads;
}

std::string Subscribe(uint32_t id, uint32_t channel) {
  return Json{{"op", "subscribe"},
              {"subscriptions", {{{"id", id}, {"channelId", channel}}}}}
      .dump();
}

std::vector<uint8_t> Base64Decode(const std::string& text) {
  static const std::string kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<uint8_t> bytes;
  uint32_t v = 0;
  int bits = 0;
  for (const char ch : text) {
    if (ch == '=') break;
    const size_t k = kAlphabet.find(ch);
    if (k == std::string::npos) throw std::invalid_argument("not base64");
    v = (v << 6) | static_cast<uint32_t>(k);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<uint8_t>(v >> bits));
    }
  }
  return bytes;
}

CameraPicture Gradient(int width, int height) {
  CameraPicture picture{width, height, {}};
  for (int k = 0; k < width * height * 3; ++k) {
    picture.rgb.push_back(static_cast<uint8_t>(k * 7));
  }
  return picture;
}

camera_image_t Picture(int jpeg_quality = 0) {
  CameraImageHeader header;
  header.robot = "snake";
  header.sender = "mrsim-camera";
  header.camera = 1;
  header.name = "snake/sm0/camera1";
  header.seq = 12;
  header.sim_time = 2.5;
  return EncodeCameraImage(header, Gradient(32, 24), jpeg_quality);
}

// The id of the channel of `topic` after connecting client 1 and hearing
// `msg` once, and that client subscribed to it as subscription 7.
uint32_t HearAndSubscribe(FoxgloveBridge& bridge, const camera_image_t& msg,
                          const std::string& topic, Json* advertised) {
  bridge.Connect(1, false, 0);
  for (const Json& c : Advertised(Lcm(bridge, "MRSIM_CAMERA_snake", msg), 1)) {
    if (c["topic"] != topic) continue;
    *advertised = c;
    const auto id = c["id"].get<uint32_t>();
    bridge.OnClientText(1, Subscribe(7, id), 0);
    return id;
  }
  return 0;
}

TEST(FoxgloveCamera, RgbPictureBecomesARawImageWithItsPixels) {
  FoxgloveBridge bridge({});
  const camera_image_t msg = Picture();
  Json channel;
  ASSERT_NE(HearAndSubscribe(bridge, msg, "/camera/snake/1", &channel), 0u);
  EXPECT_EQ(channel["schemaName"], "foxglove.RawImage");
  EXPECT_EQ(channel["encoding"], "json");
  const Json schema = Json::parse(channel["schema"].get<std::string>());
  EXPECT_EQ(schema["properties"]["data"]["contentEncoding"], "base64");

  const auto images = PayloadsTo(Lcm(bridge, "MRSIM_CAMERA_snake", msg), 1);
  ASSERT_EQ(images.size(), 1u);
  const Json& image = images[0];
  EXPECT_EQ(image["width"], 32);
  EXPECT_EQ(image["height"], 24);
  EXPECT_EQ(image["encoding"], "rgb8");
  EXPECT_EQ(image["step"], 32 * 3);
  EXPECT_EQ(image["frame_id"], "snake/sm0/camera1");
  EXPECT_EQ(image["timestamp"]["sec"], 2);
  EXPECT_EQ(image["timestamp"]["nsec"], 500'000'000);
  EXPECT_EQ(Base64Decode(image["data"]), Gradient(32, 24).rgb);
}

TEST(FoxgloveCamera, JpegPictureBecomesACompressedImageWithItsFile) {
  FoxgloveBridge bridge({});
  const camera_image_t msg = Picture(90);
  Json channel;
  ASSERT_NE(HearAndSubscribe(bridge, msg, "/camera/snake/1", &channel), 0u);
  EXPECT_EQ(channel["schemaName"], "foxglove.CompressedImage");
  const auto images = PayloadsTo(Lcm(bridge, "MRSIM_CAMERA_snake", msg), 1);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images[0]["format"], "jpeg");
  EXPECT_EQ(images[0]["frame_id"], "snake/sm0/camera1");
  EXPECT_EQ(Base64Decode(images[0]["data"]), msg.data);
}

TEST(FoxgloveCamera, MalformedPictureIsCountedAndDropped) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  camera_image_t msg = Picture();
  msg.data.resize(msg.data.size() - 3);  // one pixel short of 32 x 24
  msg.num_bytes = static_cast<int32_t>(msg.data.size());
  const BridgeOutput out = Lcm(bridge, "MRSIM_CAMERA_snake", msg);
  EXPECT_EQ(bridge.counts().lcm_malformed, 1);
  EXPECT_TRUE(Advertised(out, 1).empty());
  EXPECT_TRUE(PayloadsTo(out, 1).empty());
}

TEST(FoxgloveCamera, GenericChannelCarriesThePictureWithoutItsBytes) {
  FoxgloveBridge bridge({});
  const camera_image_t msg = Picture();
  Json channel;
  ASSERT_NE(HearAndSubscribe(bridge, msg, "MRSIM_CAMERA_snake", &channel), 0u);
  EXPECT_EQ(channel["schemaName"], "mrsim.camera_image_t");
  const Json schema = Json::parse(channel["schema"].get<std::string>());
  EXPECT_EQ(schema["properties"]["data"]["maxItems"], 0);
  EXPECT_EQ(schema["properties"]["width"]["type"], "integer");

  const auto payloads = PayloadsTo(Lcm(bridge, "MRSIM_CAMERA_snake", msg), 1);
  ASSERT_EQ(payloads.size(), 1u);
  EXPECT_EQ(payloads[0]["data"], Json::array());
  EXPECT_EQ(payloads[0]["num_bytes"], 32 * 24 * 3);
  EXPECT_EQ(payloads[0]["seq"], 12);
  EXPECT_EQ(payloads[0]["name"], "snake/sm0/camera1");
}

TEST(FoxgloveCamera, SlowClientKeepsABoundedNumberOfBytesOfPictures) {
  // Full 640 x 480 pictures, base64: ~1.2 MB each.
  ClientOutbox outbox;
  const std::string picture(640 * 480 * 4, 'A');
  for (int k = 0; k < 100; ++k) {
    ASSERT_TRUE(outbox.Push({1, true, true, picture}));
  }
  EXPECT_LE(outbox.bytes(), 32u * 1024 * 1024);
  EXPECT_GT(outbox.dropped(), 0);
}

TEST(FoxgloveCamera, Base64IsRfc4648Padded) {
  for (const auto& [in, want] :
       std::vector<std::pair<std::string, std::string>>{
           {"", "\"\""},
           {"f", "\"Zg==\""},
           {"fo", "\"Zm8=\""},
           {"foo", "\"Zm9v\""},
           {"foob", "\"Zm9vYg==\""},
           {std::string("\xff\x00\xfe", 3), "\"/wD+\""}}) {
    JsonWriter out;
    WriteBase64String(in, out);
    EXPECT_EQ(out.view(), want);
  }
}

}  // namespace
}  // namespace mrsim::foxglove
