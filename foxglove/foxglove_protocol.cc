#include "foxglove/foxglove_protocol.h"

#include <array>
#include <cstring>
#include <nlohmann/json.hpp>

namespace mrsim::foxglove {
namespace {

using Json = nlohmann::json;

// The ops a client of protocol v1 may send (text frames).
constexpr std::array<const char*, 11> kClientOps = {
    "subscribe",
    "unsubscribe",
    "advertise",
    "unadvertise",
    "getParameters",
    "setParameters",
    "subscribeParameterUpdates",
    "unsubscribeParameterUpdates",
    "subscribeConnectionGraph",
    "unsubscribeConnectionGraph",
    "fetchAsset"};

uint32_t Id(const Json& object, const char* key, const char* what) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_unsigned()) {
    throw FoxgloveProtocolError(std::string(what) + ": expected \"" + key +
                                "\" as a non-negative integer");
  }
  const uint64_t v = it->get<uint64_t>();
  if (v > UINT32_MAX) {
    throw FoxgloveProtocolError(std::string(what) + ": \"" + key +
                                "\" is over 2^32-1");
  }
  return static_cast<uint32_t>(v);
}

const Json& List(const Json& object, const char* key, const char* op) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_array()) {
    throw FoxgloveProtocolError(std::string(op) + ": expected an array \"" +
                                key + "\"");
  }
  if (it->size() > kMaxListed) {
    throw FoxgloveProtocolError(
        std::string(op) + ": " + std::to_string(it->size()) +
        " entries, at most " + std::to_string(kMaxListed) + " taken");
  }
  return *it;
}

uint32_t ReadU32(std::string_view data, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) {
    v = (v << 8) | static_cast<uint8_t>(data[at + static_cast<size_t>(k)]);
  }
  return v;
}

void PutU32(std::string& out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>(v >> (8 * k)));
}
void PutU64(std::string& out, uint64_t v) {
  for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>(v >> (8 * k)));
}

}  // namespace

std::string ChooseSubprotocol(const std::vector<std::string>& offered) {
  for (const std::string& p : offered) {
    if (p == kSubprotocolV1 || p == kSubprotocolSdk) return p;
  }
  return "";
}

ClientText ParseClientText(std::string_view text) {
  if (text.size() > kMaxTextFrame) {
    throw FoxgloveProtocolError("text frame of " + std::to_string(text.size()) +
                                " bytes, at most " +
                                std::to_string(kMaxTextFrame) + " taken");
  }
  const Json message = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) {
    throw FoxgloveProtocolError("text frame is not JSON");
  }
  if (!message.is_object()) {
    throw FoxgloveProtocolError("text frame is not a JSON object");
  }
  const auto op = message.find("op");
  if (op == message.end() || !op->is_string()) {
    throw FoxgloveProtocolError("text frame has no string \"op\"");
  }
  ClientText out;
  out.op = op->get<std::string>();
  if (out.op == "subscribe") {
    out.kind = ClientText::Kind::kSubscribe;
    for (const Json& s : List(message, "subscriptions", "subscribe")) {
      if (!s.is_object()) {
        throw FoxgloveProtocolError("subscribe: a subscription is no object");
      }
      out.subscriptions.push_back(
          {Id(s, "id", "subscribe"), Id(s, "channelId", "subscribe")});
    }
    return out;
  }
  if (out.op == "unsubscribe") {
    out.kind = ClientText::Kind::kUnsubscribe;
    for (const Json& id : List(message, "subscriptionIds", "unsubscribe")) {
      if (!id.is_number_unsigned() || id.get<uint64_t>() > UINT32_MAX) {
        throw FoxgloveProtocolError(
            "unsubscribe: a subscription id is no 32-bit unsigned integer");
      }
      out.subscription_ids.push_back(static_cast<uint32_t>(id.get<uint64_t>()));
    }
    return out;
  }
  for (const char* known : kClientOps) {
    if (out.op == known) return out;  // kUnsupported
  }
  throw FoxgloveProtocolError("unknown op \"" + out.op.substr(0, 64) + "\"");
}

ServiceCall ParseClientBinary(std::string_view data) {
  if (data.size() > kMaxBinaryFrame) {
    throw FoxgloveProtocolError(
        "binary frame of " + std::to_string(data.size()) + " bytes, at most " +
        std::to_string(kMaxBinaryFrame) + " taken");
  }
  if (data.empty()) throw FoxgloveProtocolError("empty binary frame");
  const auto opcode = static_cast<uint8_t>(data[0]);
  if (opcode == 0x01) {
    throw FoxgloveProtocolError(
        "client message data: this server takes no client publishing");
  }
  if (opcode != 0x02) {
    throw FoxgloveProtocolError("unknown binary opcode " +
                                std::to_string(opcode));
  }
  if (data.size() < 13) {
    throw FoxgloveProtocolError("service call of " +
                                std::to_string(data.size()) +
                                " bytes, its header alone is 13");
  }
  ServiceCall call;
  call.service_id = ReadU32(data, 1);
  call.call_id = ReadU32(data, 5);
  const uint32_t encoding_length = ReadU32(data, 9);
  if (encoding_length > data.size() - 13) {
    throw FoxgloveProtocolError("service call: encoding length " +
                                std::to_string(encoding_length) +
                                " runs past the frame's end");
  }
  call.encoding.assign(data.substr(13, encoding_length));
  call.payload.assign(data.substr(13 + encoding_length));
  return call;
}

std::string MessageDataFrame(uint32_t subscription_id, uint64_t timestamp_ns,
                             std::string_view payload) {
  std::string out;
  out.reserve(13 + payload.size());
  out.push_back(0x01);
  PutU32(out, subscription_id);
  PutU64(out, timestamp_ns);
  out.append(payload);
  return out;
}

std::string TimeFrame(uint64_t timestamp_ns) {
  std::string out;
  out.push_back(0x02);
  PutU64(out, timestamp_ns);
  return out;
}

std::string ServiceCallResponseFrame(uint32_t service_id, uint32_t call_id,
                                     std::string_view encoding,
                                     std::string_view payload) {
  std::string out;
  out.push_back(0x03);
  PutU32(out, service_id);
  PutU32(out, call_id);
  PutU32(out, static_cast<uint32_t>(encoding.size()));
  out.append(encoding);
  out.append(payload);
  return out;
}

}  // namespace mrsim::foxglove
