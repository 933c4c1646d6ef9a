// The Foxglove WebSocket protocol v1 on the wire (foxglove/ws-protocol's
// docs/spec.md), without sockets: what a client may send, parsed and
// checked, and the binary frames a server sends. Every byte a client sends
// is hostile: the parsers check sizes before reading, bound what they keep
// and throw FoxgloveProtocolError saying what was wrong.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mrsim::foxglove {

// The subprotocols a client may offer; the server answers with the one
// offered (foxglove.sdk.v1 is what newer clients and servers use).
inline constexpr const char* kSubprotocolV1 = "foxglove.websocket.v1";
inline constexpr const char* kSubprotocolSdk = "foxglove.sdk.v1";
// The first of `offered` the server speaks, or "" when none is.
std::string ChooseSubprotocol(const std::vector<std::string>& offered);

// A client message the server refuses: malformed, too big, an unknown op.
class FoxgloveProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Longest text frame read (a subscribe of kMaxListed ids fits).
inline constexpr size_t kMaxTextFrame = 64 * 1024;
// Longest binary frame read (a service call with its request).
inline constexpr size_t kMaxBinaryFrame = 64 * 1024;
// Most ids one subscribe / unsubscribe may list.
inline constexpr size_t kMaxListed = 1024;

struct Subscription {
  uint32_t id = 0;
  uint32_t channel_id = 0;
};

// A text frame of a client. Ops the server does not offer (client
// publishing, parameters, assets, ...) are kind kUnsupported with their op.
struct ClientText {
  enum class Kind { kSubscribe, kUnsubscribe, kUnsupported };
  Kind kind = Kind::kUnsupported;
  std::string op;
  std::vector<Subscription> subscriptions;  // kSubscribe
  std::vector<uint32_t> subscription_ids;   // kUnsubscribe
};

// Throws FoxgloveProtocolError: not a JSON object, no string "op", an op
// that is no op of the protocol, fields of the wrong type, more than
// kMaxListed ids, a frame over kMaxTextFrame.
ClientText ParseClientText(std::string_view text);

// A Service Call Request (binary opcode 0x02).
struct ServiceCall {
  uint32_t service_id = 0;
  uint32_t call_id = 0;
  std::string encoding;
  std::string payload;
};

// Throws FoxgloveProtocolError: empty, another opcode (client message data:
// the server does not take client publishing), lengths past the frame's
// end, a frame over kMaxBinaryFrame.
ServiceCall ParseClientBinary(std::string_view data);

// Server binary frames (little-endian, as the spec says).
std::string MessageDataFrame(uint32_t subscription_id, uint64_t timestamp_ns,
                             std::string_view payload);
std::string TimeFrame(uint64_t timestamp_ns);
std::string ServiceCallResponseFrame(uint32_t service_id, uint32_t call_id,
                                     std::string_view encoding,
                                     std::string_view payload);

}  // namespace mrsim::foxglove
