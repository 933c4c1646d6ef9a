// What a Foxglove client sends mrsim-foxglove (foxglove/foxglove_bridge.h):
// any bytes as one text frame (first byte even) or binary frame (odd),
// after the client subscribed to everything. Never a crash; every refusal
// is a status or a service-call failure; what the bridge keeps stays
// bounded.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "foxglove/foxglove_bridge.h"
#include "foxglove/foxglove_protocol.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim::foxglove;
  if (size == 0) return 0;
  const std::string_view frame(reinterpret_cast<const char*>(data + 1),
                               size - 1);
  try {
    ParseClientText(frame);
  } catch (const FoxgloveProtocolError&) {
  }
  try {
    ParseClientBinary(frame);
  } catch (const FoxgloveProtocolError&) {
  }
  FoxgloveBridgeOptions options;
  options.max_refusals = 1000000;
  FoxgloveBridge bridge(options);
  bridge.Connect(1, true, 0);
  bridge.OnClientText(
      1, R"({"op":"subscribe","subscriptions":[{"id":7,"channelId":1}]})", 0);
  for (int k = 0; k < 3; ++k) {
    const BridgeOutput out = (data[0] % 2 == 0)
                                 ? bridge.OnClientText(1, frame, 1)
                                 : bridge.OnClientBinary(1, frame, 1);
    if (out.send.size() + out.controls.size() > 2 * kMaxListed + 2) {
      std::abort();
    }
  }
  bridge.Tick(UINT64_MAX);
  bridge.Disconnect(1);
  return 0;
}
