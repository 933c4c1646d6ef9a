// FoxgloveBridge driven in-process: what a Foxglove client gets for a
// simulation's messages, and what it may and may not do.
#include "foxglove/foxglove_bridge.h"

#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "foxglove/foxglove_protocol.h"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tests/logger/test_messages.h"

namespace mrsim::foxglove {
namespace {

using Json = nlohmann::json;

template <class Message>
std::vector<uint8_t> Encode(const Message& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

template <class Message>
BridgeOutput Lcm(FoxgloveBridge& bridge, const std::string& channel,
                 const Message& m) {
  const auto buf = Encode(m);
  return bridge.OnLcm(channel, buf.data(), buf.size(), 0);
}

std::vector<Json> TextsTo(const BridgeOutput& out, ClientId client) {
  std::vector<Json> texts;
  for (const Outgoing& o : out.send) {
    if (o.client == client && !o.binary) texts.push_back(Json::parse(o.data));
  }
  return texts;
}

struct Data {
  uint32_t subscription;
  uint64_t time;
  Json payload;
};
// The message data frames to `client`, decoded.
std::vector<Data> DataTo(const BridgeOutput& out, ClientId client) {
  std::vector<Data> data;
  for (const Outgoing& o : out.send) {
    if (o.client != client || !o.binary || o.data[0] != 0x01) continue;
    Data d{};
    std::memcpy(&d.subscription, o.data.data() + 1, 4);
    std::memcpy(&d.time, o.data.data() + 5, 8);
    d.payload = Json::parse(o.data.substr(13));
    data.push_back(d);
  }
  return data;
}

std::vector<uint64_t> TimesTo(const BridgeOutput& out, ClientId client) {
  std::vector<uint64_t> times;
  for (const Outgoing& o : out.send) {
    if (o.client != client || !o.binary || o.data[0] != 0x02) continue;
    uint64_t t = 0;
    std::memcpy(&t, o.data.data() + 1, 8);
    times.push_back(t);
  }
  return times;
}

std::string Subscribe(uint32_t id, uint32_t channel) {
  return Json{{"op", "subscribe"},
              {"subscriptions", {{{"id", id}, {"channelId", channel}}}}}
      .dump();
}

std::string Call(uint32_t service, uint32_t call, const std::string& json) {
  std::string frame(1, '\x02');
  for (const uint32_t v : {service, call, 4u}) {
    for (int k = 0; k < 4; ++k)
      frame.push_back(static_cast<char>(v >> (8 * k)));
  }
  return frame + "json" + json;
}

// The channel advertised with this topic, or 0.
uint32_t ChannelId(const std::vector<Json>& texts, const std::string& topic) {
  for (const Json& t : texts) {
    if (t["op"] != "advertise") continue;
    for (const Json& c : t["channels"]) {
      if (c["topic"] == topic) return c["id"].get<uint32_t>();
    }
  }
  return 0;
}

TEST(FoxgloveBridge, ConnectSendsServerInfoChannelsWithJsonSchemasAndServices) {
  FoxgloveBridge bridge({});
  const auto texts = TextsTo(bridge.Connect(1, false, 0), 1);
  ASSERT_EQ(texts.size(), 3u);
  EXPECT_EQ(texts[0]["op"], "serverInfo");
  EXPECT_EQ(texts[0]["capabilities"], Json({"time", "services"}));
  EXPECT_EQ(texts[1]["op"], "advertise");
  std::vector<std::string> names;
  for (const Json& c : texts[1]["channels"]) {
    EXPECT_EQ(c["encoding"], "json");
    EXPECT_EQ(c["schemaEncoding"], "jsonschema");
    const Json schema = Json::parse(c["schema"].get<std::string>());
    EXPECT_EQ(schema["type"], "object");
    names.push_back(c["schemaName"]);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"foxglove.SceneUpdate",
                                             "foxglove.FrameTransforms"}));
  EXPECT_EQ(texts[2]["op"], "advertiseServices");
  std::vector<std::string> services;
  for (const Json& s : texts[2]["services"]) {
    services.push_back(s["name"]);
    EXPECT_TRUE(Json::parse(s["requestSchema"].get<std::string>()).is_object());
  }
  EXPECT_EQ(services, (std::vector<std::string>{"/mrsim/pause", "/mrsim/resume",
                                                "/mrsim/step", "/mrsim/speed",
                                                "/mrsim/reset"}));
}

TEST(FoxgloveBridge, SubscribersGetTheSceneAndTransformsEqualToTheState) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  const robot_state_t state = testing::KnownRobotState(5, 3, 1);
  Lcm(bridge, "MRSIM_STATE_snake", state);
  const auto scene = DataTo(
      bridge.OnClientText(1, Subscribe(10, FoxgloveBridge::kSceneChannel), 0),
      1);
  ASSERT_EQ(scene.size(), 1u);
  EXPECT_EQ(scene[0].subscription, 10u);
  // The ground, six frames and one sensor module.
  const Json& entities = scene[0].payload["entities"];
  ASSERT_EQ(entities.size(), 8u);
  EXPECT_EQ(entities[1]["frame_id"], "snake/frame_0");
  EXPECT_EQ(entities[7]["frame_id"], "snake/sensor_0");
  EXPECT_EQ(scene[0].payload["deletions"][0]["type"], 1);

  bridge.OnClientText(1, Subscribe(11, FoxgloveBridge::kTransformsChannel), 0);
  const robot_state_t next = testing::KnownRobotState(6, 3, 1);
  const auto out = Lcm(bridge, "MRSIM_STATE_snake", next);
  const auto tf = DataTo(out, 1);
  ASSERT_EQ(tf.size(), 1u);
  EXPECT_EQ(tf[0].subscription, 11u);
  EXPECT_EQ(tf[0].time, static_cast<uint64_t>(next.utime) * 1000);
  const Json& transforms = tf[0].payload["transforms"];
  ASSERT_EQ(transforms.size(), 7u);
  for (int k = 0; k < 6; ++k) {
    const Json& t = transforms[k];
    EXPECT_EQ(t["parent_frame_id"], "world");
    EXPECT_EQ(t["child_frame_id"], "snake/frame_" + std::to_string(k));
    const pose_t& p = next.frames[k];
    EXPECT_EQ(t["translation"]["x"].get<double>(), p.position[0]);
    EXPECT_EQ(t["translation"]["y"].get<double>(), p.position[1]);
    EXPECT_EQ(t["translation"]["z"].get<double>(), p.position[2]);
    EXPECT_EQ(t["rotation"]["w"].get<double>(), p.orientation[0]);
    EXPECT_EQ(t["rotation"]["x"].get<double>(), p.orientation[1]);
    EXPECT_EQ(t["rotation"]["y"].get<double>(), p.orientation[2]);
    EXPECT_EQ(t["rotation"]["z"].get<double>(), p.orientation[3]);
  }
  EXPECT_EQ(transforms[6]["translation"]["x"].get<double>(),
            next.sensor_modules[0].pose.position[0]);
}

TEST(FoxgloveBridge, ASceneThatChangesShapeIsSentAgain) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  bridge.OnClientText(1, Subscribe(1, FoxgloveBridge::kSceneChannel), 0);
  EXPECT_EQ(DataTo(Lcm(bridge, "MRSIM_STATE_a",
                       testing::KnownRobotState(1, 2, 0, "a")),
                   1)
                .size(),
            1u);
  // Same shape: no new scene.
  EXPECT_EQ(DataTo(Lcm(bridge, "MRSIM_STATE_a",
                       testing::KnownRobotState(2, 2, 0, "a")),
                   1)
                .size(),
            0u);
  scene_state_t objects{};
  objects.utime = 3000;
  objects.num_objects = 1;
  objects.object_index = {4};
  objects.poses.resize(1);
  const auto data = DataTo(Lcm(bridge, "MRSIM_SCENE", objects), 1);
  ASSERT_EQ(data.size(), 1u);
  EXPECT_EQ(data[0].payload["entities"].back()["id"], "scene/object_4");
}

TEST(FoxgloveBridge, OtherChannelsAreAdvertisedWhenHeardAndSentAsJson) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  sim_status_t status{};
  status.seq = 9;
  status.mode = sim_status_t::PAUSED;
  const auto first = Lcm(bridge, "MRSIM_SIM_STATUS", status);
  const uint32_t id = ChannelId(TextsTo(first, 1), "MRSIM_SIM_STATUS");
  ASSERT_NE(id, 0u);
  bridge.OnClientText(1, Subscribe(3, id), 0);
  const auto data = DataTo(Lcm(bridge, "MRSIM_SIM_STATUS", status), 1);
  ASSERT_EQ(data.size(), 1u);
  EXPECT_EQ(data[0].payload["seq"], 9);
  EXPECT_EQ(data[0].payload["mode"], 1);
  // A client connecting later is told of the channel at once.
  EXPECT_EQ(
      ChannelId(TextsTo(bridge.Connect(2, false, 0), 2), "MRSIM_SIM_STATUS"),
      id);
}

TEST(FoxgloveBridge, TimeNeverGoesBackEvenAfterAReset) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  std::vector<uint64_t> times;
  for (const int64_t seq : {1, 2, 3, 0, 1, 2}) {  // reset after 3
    const auto t = TimesTo(
        Lcm(bridge, "MRSIM_STATE_snake", testing::KnownRobotState(seq, 1, 0)),
        1);
    times.insert(times.end(), t.begin(), t.end());
  }
  ASSERT_GE(times.size(), 4u);
  for (size_t k = 1; k < times.size(); ++k) EXPECT_GT(times[k], times[k - 1]);
}

TEST(FoxgloveBridge, ControlsAreRefusedForAClientNotAllowed) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  const auto out = bridge.OnClientBinary(1, Call(1, 42, "{}"), 0);
  EXPECT_TRUE(out.controls.empty());
  const auto texts = TextsTo(out, 1);
  ASSERT_EQ(texts.size(), 1u);
  EXPECT_EQ(texts[0]["op"], "serviceCallFailure");
  EXPECT_EQ(texts[0]["callId"], 42);
  EXPECT_NE(texts[0]["message"].get<std::string>().find("refused"),
            std::string::npos);
  EXPECT_EQ(bridge.counts().refused_calls, 1);
}

TEST(FoxgloveBridge, AnAllowedCallPublishesAControlAndAnswersWithTheStatus) {
  FoxgloveBridgeOptions options;
  options.first_control_seq = 100;
  FoxgloveBridge bridge(options);
  bridge.Connect(1, true, 0);
  const auto out = bridge.OnClientBinary(1, Call(3, 7, R"({"steps":4})"), 0);
  ASSERT_EQ(out.controls.size(), 1u);
  EXPECT_EQ(out.controls[0].command, int8_t{sim_control_t::STEP});
  EXPECT_EQ(out.controls[0].steps, 4);
  EXPECT_EQ(out.controls[0].seq, 100);
  EXPECT_EQ(out.controls[0].sender, "mrsim-foxglove");
  sim_status_t ack{};
  ack.control_seq = 100;
  ack.control_sender = "mrsim-foxglove";
  ack.control_ok = true;
  const auto answer = Lcm(bridge, "MRSIM_SIM_STATUS", ack);
  // The response, besides the status channel's advertisement.
  std::string frame;
  for (const Outgoing& o : answer.send) {
    if (o.binary) frame = o.data;
  }
  ASSERT_GT(frame.size(), 17u);
  ASSERT_EQ(frame[0], 0x03);
  EXPECT_EQ(frame[5], 7);  // call id
  EXPECT_EQ(Json::parse(frame.substr(13 + 4)),
            Json({{"ok", true}, {"message", ""}}));
}

TEST(FoxgloveBridge, ACallTheSimulatorNeverAnswersFails) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, true, 0);
  ASSERT_EQ(bridge.OnClientBinary(1, Call(1, 1, "{}"), 0).controls.size(), 1u);
  EXPECT_TRUE(bridge.Tick(1'000'000'000).send.empty());
  const auto texts = TextsTo(bridge.Tick(10'000'000'000), 1);
  ASSERT_EQ(texts.size(), 1u);
  EXPECT_EQ(texts[0]["op"], "serviceCallFailure");
}

TEST(FoxgloveBridge, BadRequestsAreRefusedWithTheirReason) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, true, 0);
  for (const std::string& request :
       {std::string(R"({"speed":-1})"), std::string("not json")}) {
    const auto out = bridge.OnClientBinary(1, Call(4, 1, request), 0);
    EXPECT_TRUE(out.controls.empty()) << request;
    EXPECT_EQ(TextsTo(out, 1).at(0)["op"], "serviceCallFailure");
  }
  EXPECT_EQ(bridge.counts().refused_calls, 2);
}

TEST(FoxgloveBridge, MalformedAndUnknownMessagesAreRefusedAndCounted) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  for (const char* text : {"{", "[]", R"({"op":7})", R"({"op":"fly"})",
                           R"({"op":"subscribe","subscriptions":7})"}) {
    const auto texts = TextsTo(bridge.OnClientText(1, text, 0), 1);
    ASSERT_EQ(texts.size(), 1u) << text;
    EXPECT_EQ(texts[0]["op"], "status");
    EXPECT_EQ(texts[0]["level"], 2);
  }
  EXPECT_EQ(bridge.counts().malformed, 5);
  EXPECT_EQ(bridge.counts().unknown_op, 1);
  bridge.OnClientText(1, R"({"op":"getParameters","parameterNames":[]})", 0);
  EXPECT_EQ(bridge.counts().unsupported, 1);
  EXPECT_EQ(bridge.counts().malformed, 5);
}

TEST(FoxgloveBridge, ASubscriptionFloodIsRefusedAndItsClientClosed) {
  FoxgloveBridgeOptions options;
  options.max_refusals = 50;
  FoxgloveBridge bridge(options);
  bridge.Connect(1, false, 0);
  ASSERT_TRUE(bridge.OnClientText(1, Subscribe(1, 1), 0).close.empty());
  bool closed = false;
  int statuses = 0;
  for (uint32_t k = 0; k < 100 && !closed; ++k) {
    const auto out = bridge.OnClientText(1, Subscribe(1, 1), 0);  // in use
    statuses += static_cast<int>(TextsTo(out, 1).size());
    closed = !out.close.empty();
  }
  EXPECT_TRUE(closed);
  EXPECT_EQ(bridge.counts().refused_subscriptions, 50);
  EXPECT_EQ(bridge.counts().closed, 1);
  // Statuses are bounded: the rest only counted.
  EXPECT_LE(statuses, 25);
}

TEST(FoxgloveBridge, NothingIsEncodedForChannelsNobodySubscribed) {
  FoxgloveBridge bridge({});
  bridge.Connect(1, false, 0);
  Lcm(bridge, "MRSIM_STATE_snake", testing::KnownRobotState(1, 3, 0));
  const auto out =
      Lcm(bridge, "MRSIM_STATE_snake", testing::KnownRobotState(2, 3, 0));
  EXPECT_TRUE(DataTo(out, 1).empty());
  EXPECT_EQ(TimesTo(out, 1).size(), 1u);
}

TEST(FoxgloveBridge, UnknownAndMalformedLcmMessagesAreCounted) {
  FoxgloveBridge bridge({});
  const std::string junk = "12345678abc";
  bridge.OnLcm("MRSIM_X", junk.data(), junk.size(), 0);
  EXPECT_EQ(bridge.counts().lcm_unknown, 1);
  auto buf = Encode(testing::KnownRobotState(1, 3, 0));
  buf.resize(buf.size() / 2);
  bridge.OnLcm("MRSIM_STATE_snake", buf.data(), buf.size(), 0);
  EXPECT_EQ(bridge.counts().lcm_malformed, 1);
}

}  // namespace
}  // namespace mrsim::foxglove
