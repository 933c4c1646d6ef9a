// The protocol's parsing of client frames, the server's binary frames, the
// per-client outbox and who may control.
#include "foxglove/foxglove_protocol.h"

#include <gtest/gtest.h>

#include <string>

#include "foxglove/client_outbox.h"
#include "foxglove/control_access.h"

namespace mrsim::foxglove {
namespace {

TEST(FoxgloveProtocol, AnswersWithTheSubprotocolOffered) {
  EXPECT_EQ(ChooseSubprotocol({"foxglove.websocket.v1"}),
            "foxglove.websocket.v1");
  EXPECT_EQ(ChooseSubprotocol({"x", "foxglove.sdk.v1"}), "foxglove.sdk.v1");
  EXPECT_EQ(ChooseSubprotocol({"chat"}), "");
  EXPECT_EQ(ChooseSubprotocol({}), "");
}

TEST(FoxgloveProtocol, ParsesSubscribeAndUnsubscribe) {
  const ClientText s = ParseClientText(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},)"
      R"({"id":1,"channelId":5}]})");
  ASSERT_EQ(s.kind, ClientText::Kind::kSubscribe);
  ASSERT_EQ(s.subscriptions.size(), 2u);
  EXPECT_EQ(s.subscriptions[1].id, 1u);
  EXPECT_EQ(s.subscriptions[1].channel_id, 5u);
  const ClientText u =
      ParseClientText(R"({"op":"unsubscribe","subscriptionIds":[0,1]})");
  ASSERT_EQ(u.kind, ClientText::Kind::kUnsubscribe);
  EXPECT_EQ(u.subscription_ids, (std::vector<uint32_t>{0, 1}));
}

TEST(FoxgloveProtocol, RefusesMalformedFramesSayingWhy) {
  const auto refused = [](const std::string& text) {
    try {
      ParseClientText(text);
    } catch (const FoxgloveProtocolError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused("{"), "text frame is not JSON");
  EXPECT_EQ(refused("[1]"), "text frame is not a JSON object");
  EXPECT_EQ(refused(R"({"op":1})"), "text frame has no string \"op\"");
  EXPECT_EQ(refused(R"({"op":"fly"})"), "unknown op \"fly\"");
  EXPECT_NE(
      refused(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})")
          .find("non-negative integer"),
      std::string::npos);
  EXPECT_NE(
      refused(
          R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})")
          .find("over 2^32-1"),
      std::string::npos);
  std::string many = R"({"op":"unsubscribe","subscriptionIds":[0)";
  for (size_t k = 0; k < kMaxListed; ++k) many += ",0";
  EXPECT_NE(refused(many + "]}").find("at most 1024"), std::string::npos);
  EXPECT_NE(refused(std::string(kMaxTextFrame + 1, ' ')).find("text frame of"),
            std::string::npos);
}

TEST(FoxgloveProtocol, ServiceCallsAreReadWithinTheirFrame) {
  std::string frame = std::string("\x02", 1) + std::string("\x04\0\0\0", 4) +
                      std::string("\x09\0\0\0", 4) +
                      std::string("\x04\0\0\0", 4) + "json{}";
  const ServiceCall call = ParseClientBinary(frame);
  EXPECT_EQ(call.service_id, 4u);
  EXPECT_EQ(call.call_id, 9u);
  EXPECT_EQ(call.encoding, "json");
  EXPECT_EQ(call.payload, "{}");
  frame[9] = '\x7f';  // encoding length past the end
  EXPECT_THROW(ParseClientBinary(frame), FoxgloveProtocolError);
  EXPECT_THROW(ParseClientBinary(frame.substr(0, 12)), FoxgloveProtocolError);
  EXPECT_THROW(ParseClientBinary(""), FoxgloveProtocolError);
  EXPECT_THROW(ParseClientBinary(std::string("\x01\0\0\0\0{}", 7)),
               FoxgloveProtocolError);
}

TEST(FoxgloveProtocol, BinaryFramesAreLittleEndianAsTheSpecSays) {
  EXPECT_EQ(TimeFrame(0x0102030405060708ull),
            std::string("\x02\x08\x07\x06\x05\x04\x03\x02\x01", 9));
  EXPECT_EQ(MessageDataFrame(0x11223344u, 1, "{}"),
            std::string("\x01\x44\x33\x22\x11\x01\0\0\0\0\0\0\0{}", 15));
  EXPECT_EQ(ServiceCallResponseFrame(1, 2, "json", "{}"),
            std::string("\x03\x01\0\0\0\x02\0\0\0\x04\0\0\0json{}", 19));
}

TEST(ClientOutbox, ASlowClientLosesItsOldestDataNeverItsControlFrames) {
  ClientOutbox box(4, 1 << 20);
  ASSERT_TRUE(box.Push({1, false, false, "advertise"}));
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(box.Push({1, true, true, "data" + std::to_string(k)}));
  }
  EXPECT_EQ(box.size(), 4u);
  EXPECT_EQ(box.dropped(), 7);
  EXPECT_EQ(box.Pop()->data, "advertise");
  EXPECT_EQ(box.Pop()->data, "data7");
  EXPECT_EQ(box.Pop()->data, "data8");
  EXPECT_EQ(box.Pop()->data, "data9");
  EXPECT_FALSE(box.Pop().has_value());
  EXPECT_EQ(box.bytes(), 0u);
}

TEST(ClientOutbox, ControlFramesThatCannotFitMeanClosingTheClient) {
  ClientOutbox box(2, 1 << 20);
  EXPECT_TRUE(box.Push({1, false, false, "a"}));
  EXPECT_TRUE(box.Push({1, false, false, "b"}));
  EXPECT_FALSE(box.Push({1, false, false, "c"}));
  EXPECT_TRUE(box.Push({1, true, true, "data"}));  // dropped, counted
  EXPECT_EQ(box.dropped(), 1);
  ClientOutbox small(100, 8);
  EXPECT_TRUE(small.Push({1, true, true, "0123456789"}));
  EXPECT_EQ(small.dropped(), 1);
  EXPECT_TRUE(small.empty());
}

TEST(ControlAccess, OnlyThisHostByDefaultOnlyTheTokenWithAKey) {
  EXPECT_TRUE(MayControl(true, "", ""));
  EXPECT_FALSE(MayControl(false, "", ""));
  EXPECT_FALSE(MayControl(false, "token=", ""));
  const std::string token = "00ff";
  EXPECT_FALSE(MayControl(true, "", token));
  EXPECT_FALSE(MayControl(true, "token=00fe", token));
  EXPECT_TRUE(MayControl(false, "token=00ff", token));
  EXPECT_TRUE(MayControl(false, "a=1&token=00ff&b", token));
  EXPECT_FALSE(MayControl(false, "xtoken=00ff", token));
}

}  // namespace
}  // namespace mrsim::foxglove
