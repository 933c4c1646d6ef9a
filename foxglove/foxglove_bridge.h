// The logic of mrsim-foxglove, without sockets: it takes the LCM messages
// of a simulation and what Foxglove clients send, each with the current
// time, and returns what to send to which client and which sim_control_t
// to publish. It offers
//  - "/mrsim/scene" (foxglove.SceneUpdate): every robot, sensor module,
//    scene object and a ground plane; sent when a client subscribes and
//    when the scene's shape changes;
//  - "/mrsim/tf" (foxglove.FrameTransforms): each state's frame poses;
//  - every mrsim LCM channel heard, by its name, as JSON with the JSON
//    Schema generated from its .lcm file (mrsim/message_json.hpp);
//    camera_image_t without its bytes (foxglove/camera_image_json.h);
//  - each camera heard as "/camera/<robot>/<camera>": foxglove.RawImage
//    (rgb8) or foxglove.CompressedImage (jpeg), checked by
//    DecodeCameraImage;
//  - sim time as the protocol's `time` (it never goes back: after a reset
//    the timeline goes on from where it was);
//  - the simulator's controls as services (/mrsim/pause, resume, step,
//    speed, reset), refused for a client not allowed to control.
// Bad client input is refused with a status message and counted; a client
// that keeps sending it is closed. Memory is bounded: channels,
// subscriptions, pending calls and statuses have fixed limits.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "foxglove/scene_model.h"
#include "lcmtypes/json/json_writer.h"
#include "mrsim/message_json.hpp"
#include "mrsim/sim_control_t.hpp"

namespace mrsim::foxglove {

using ClientId = uint64_t;

struct FoxgloveBridgeOptions {
  std::string prefix = "MRSIM";
  // serverInfo's name, and the sender of the sim_control_t it publishes.
  std::string name = "mrsim-foxglove";
  // The first sim_control_t seq (the simulator wants a sender's seqs to
  // grow: a restarted bridge starts from the wall clock).
  int64_t first_control_seq = 1;
  // A service call the simulator does not answer within this fails.
  int64_t service_timeout_ns = 5'000'000'000;
  size_t max_channels = 256;
  size_t max_subscriptions = 512;  // per client
  // A client whose refused messages pass this is closed.
  int max_refusals = 200;
};

// One frame for one client. Droppable frames (message data, time) may be
// dropped by a client's outbox when the client falls behind; the others
// (serverInfo, advertise, responses, statuses) are never dropped.
struct Outgoing {
  ClientId client = 0;
  bool binary = false;
  bool droppable = false;
  std::string data;
};

struct BridgeOutput {
  std::vector<Outgoing> send;
  std::vector<sim_control_t> controls;  // to publish on SimControlChannel
  std::vector<ClientId> close;          // clients to disconnect
};

class FoxgloveBridge {
 public:
  static constexpr uint32_t kSceneChannel = 1;
  static constexpr uint32_t kTransformsChannel = 2;

  struct Counts {
    int64_t clients = 0;      // connected now
    int64_t malformed = 0;    // client frames that did not parse
    int64_t unknown_op = 0;   // ... of those, unknown ops
    int64_t unsupported = 0;  // ops of the protocol this server does not offer
    int64_t refused_subscriptions = 0;
    int64_t refused_calls = 0;  // not allowed, unknown service, bad request
    int64_t closed = 0;         // clients closed for refusals
    int64_t lcm_unknown = 0;    // LCM messages of no mrsim type
    int64_t lcm_malformed = 0;
    int64_t channels_over_limit = 0;
  };

  explicit FoxgloveBridge(FoxgloveBridgeOptions options);

  // A client connected; `may_control` says whether its service calls are
  // carried out. Returns serverInfo, advertise and advertiseServices.
  BridgeOutput Connect(ClientId client, bool may_control, uint64_t now_ns);
  void Disconnect(ClientId client);
  BridgeOutput OnClientText(ClientId client, std::string_view text,
                            uint64_t now_ns);
  BridgeOutput OnClientBinary(ClientId client, std::string_view data,
                              uint64_t now_ns);
  // One raw LCM message (signature trailer already removed).
  BridgeOutput OnLcm(const std::string& channel, const void* data, size_t size,
                     uint64_t now_ns);
  // Fails service calls the simulator did not answer in time.
  BridgeOutput Tick(uint64_t now_ns);

  const Counts& counts() const { return counts_; }
  // The protocol's time now (ns): sim time, never going back.
  uint64_t timeline_ns() const { return timeline_ns_; }

 private:
  struct Channel {
    uint32_t id = 0;
    std::string topic;
    std::string schema_name;
    const char* schema = nullptr;
    const MessageJsonType* type = nullptr;  // JSON channels
  };
  struct Client {
    bool may_control = false;
    std::map<uint32_t, uint32_t> channel_of;  // subscription id -> channel
    std::map<uint32_t, uint32_t> sub_of;      // channel -> subscription id
    int refusals = 0;
  };
  struct PendingCall {
    ClientId client = 0;
    uint32_t service_id = 0;
    uint32_t call_id = 0;
    int64_t seq = 0;
    uint64_t deadline_ns = 0;
  };

  std::string AdvertiseJson(const std::vector<const Channel*>& channels) const;
  std::string ServerInfoJson() const;
  static std::string AdvertiseServicesJson();
  void Refuse(ClientId client, Client& c, const std::string& why,
              BridgeOutput& out);
  void SendToSubscribers(uint32_t channel, std::string_view payload,
                         uint64_t time_ns, bool droppable, BridgeOutput& out);
  bool AnySubscriber(uint32_t channel) const;
  void CallService(ClientId client, Client& c, std::string_view data,
                   uint64_t now_ns, BridgeOutput& out);
  void Fail(ClientId client, uint32_t service_id, uint32_t call_id,
            const std::string& message, BridgeOutput& out);
  void AdvanceTime(int64_t utime, BridgeOutput& out);
  Channel* ChannelFor(const std::string& topic, const MessageJsonType* type,
                      BridgeOutput& out);
  Channel* NewChannel(Channel channel, BridgeOutput& out);
  void OnCameraImage(const std::string& channel, const MessageJsonType* type,
                     const void* data, size_t size, BridgeOutput& out);

  FoxgloveBridgeOptions options_;
  std::vector<Channel> channels_;  // index id - 1
  std::map<std::string, uint32_t> channel_of_topic_;
  std::map<ClientId, Client> clients_;
  std::vector<PendingCall> pending_;
  SceneModel scene_;
  JsonWriter json_;
  Counts counts_;
  int64_t next_control_seq_;
  uint64_t timeline_ns_ = 0;
  int64_t last_sim_ns_ = -1;
  uint64_t offset_ns_ = 0;
  bool time_sent_ = false;
  std::string session_id_;
};

}  // namespace mrsim::foxglove
