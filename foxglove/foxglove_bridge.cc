#include "foxglove/foxglove_bridge.h"

#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "camera/camera_image_codec.h"
#include "foxglove/camera_image_json.h"
#include "foxglove/foxglove_protocol.h"
#include "foxglove/foxglove_schemas.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "mrsim/camera_image_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tools/sim_control_request.h"

namespace mrsim::foxglove {
namespace {

using Json = nlohmann::json;

// Statuses explaining refusals sent to one client; later ones are counted.
constexpr int kMaxStatuses = 20;
// Service calls waiting for the simulator's answer, over all clients.
constexpr size_t kMaxPendingCalls = 64;

struct Service {
  uint32_t id;
  const char* name;
  const char* word;  // mrsim-ctl's word for it (tools/sim_control_request.h)
  const char* const* request_schema;
};
const Service kServices[] = {
    {1, "/mrsim/pause", "pause", &kEmptyRequestSchema},
    {2, "/mrsim/resume", "resume", &kEmptyRequestSchema},
    {3, "/mrsim/step", "step", &kStepRequestSchema},
    {4, "/mrsim/speed", "speed", &kSpeedRequestSchema},
    {5, "/mrsim/reset", "reset", &kEmptyRequestSchema},
};

const Service* FindService(uint32_t id) {
  for (const Service& s : kServices) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

int64_t Fingerprint(const void* data, size_t size) {
  if (size < 8) return 0;
  const auto* p = static_cast<const uint8_t*>(data);
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v = (v << 8) | p[k];
  return static_cast<int64_t>(v);
}

std::string StatusJson(int level, const std::string& message) {
  return Json{{"op", "status"}, {"level", level}, {"message", message}}.dump(
      -1, ' ', false, Json::error_handler_t::replace);
}

// The words mrsim-ctl would take for this call ("step 10").
std::vector<std::string> Words(const Service& service,
                               std::string_view payload) {
  std::vector<std::string> words = {service.word};
  if (payload.empty()) payload = "{}";
  const Json request = Json::parse(payload, nullptr, false);
  if (request.is_discarded() || !request.is_object()) {
    throw std::invalid_argument("the request is not a JSON object");
  }
  if (service.id == 3) {
    const auto steps = request.find("steps");
    if (steps == request.end()) {
      words.push_back("1");
    } else if (steps->is_number_integer()) {
      words.push_back(std::to_string(steps->get<int64_t>()));
    } else {
      throw std::invalid_argument("\"steps\": expected an integer");
    }
  } else if (service.id == 4) {
    const auto speed = request.find("speed");
    if (speed == request.end() || !speed->is_number()) {
      throw std::invalid_argument("\"speed\": expected a number");
    }
    words.push_back(Json(speed->get<double>()).dump());
  }
  return words;
}

}  // namespace

FoxgloveBridge::FoxgloveBridge(FoxgloveBridgeOptions options)
    : options_(std::move(options)),
      next_control_seq_(options_.first_control_seq),
      session_id_(std::to_string(options_.first_control_seq)) {
  channels_.push_back({kSceneChannel, "/mrsim/scene", "foxglove.SceneUpdate",
                       kSceneUpdateSchema, nullptr});
  channels_.push_back({kTransformsChannel, "/mrsim/tf",
                       "foxglove.FrameTransforms", kFrameTransformsSchema,
                       nullptr});
  for (const Channel& c : channels_) channel_of_topic_[c.topic] = c.id;
}

std::string FoxgloveBridge::ServerInfoJson() const {
  return Json{{"op", "serverInfo"},
              {"name", options_.name},
              {"capabilities", {"time", "services"}},
              {"supportedEncodings", {"json"}},
              {"metadata", {{"prefix", options_.prefix}}},
              {"sessionId", session_id_}}
      .dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string FoxgloveBridge::AdvertiseJson(
    const std::vector<const Channel*>& channels) const {
  Json list = Json::array();
  for (const Channel* c : channels) {
    list.push_back({{"id", c->id},
                    {"topic", c->topic},
                    {"encoding", "json"},
                    {"schemaName", c->schema_name},
                    {"schema", c->schema},
                    {"schemaEncoding", "jsonschema"}});
  }
  return Json{{"op", "advertise"}, {"channels", list}}.dump(
      -1, ' ', false, Json::error_handler_t::replace);
}

std::string FoxgloveBridge::AdvertiseServicesJson() {
  Json list = Json::array();
  for (const Service& s : kServices) {
    list.push_back({{"id", s.id},
                    {"name", s.name},
                    {"type", std::string("mrsim.") + s.word},
                    {"requestSchema", *s.request_schema},
                    {"responseSchema", kControlResponseSchema}});
  }
  return Json{{"op", "advertiseServices"}, {"services", list}}.dump();
}

BridgeOutput FoxgloveBridge::Connect(ClientId client, bool may_control,
                                     uint64_t /*now_ns*/) {
  BridgeOutput out;
  Client& c = clients_[client];
  c = Client{};
  c.may_control = may_control;
  counts_.clients = static_cast<int64_t>(clients_.size());
  out.send.push_back({client, false, false, ServerInfoJson()});
  std::vector<const Channel*> all;
  for (const Channel& ch : channels_) all.push_back(&ch);
  out.send.push_back({client, false, false, AdvertiseJson(all)});
  out.send.push_back({client, false, false, AdvertiseServicesJson()});
  if (time_sent_) {
    out.send.push_back({client, true, true, TimeFrame(timeline_ns_)});
  }
  return out;
}

void FoxgloveBridge::Disconnect(ClientId client) {
  clients_.erase(client);
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(),
                                [client](const PendingCall& p) {
                                  return p.client == client;
                                }),
                 pending_.end());
  counts_.clients = static_cast<int64_t>(clients_.size());
}

void FoxgloveBridge::Refuse(ClientId client, Client& c, const std::string& why,
                            BridgeOutput& out) {
  ++c.refusals;
  if (c.refusals <= kMaxStatuses) {
    out.send.push_back({client, false, false, StatusJson(2, why)});
  }
  if (c.refusals == options_.max_refusals) {
    ++counts_.closed;
    out.send.push_back(
        {client, false, false,
         StatusJson(2, "too many refused messages; closing the connection")});
    out.close.push_back(client);
  }
}

BridgeOutput FoxgloveBridge::OnClientText(ClientId client,
                                          std::string_view text,
                                          uint64_t now_ns) {
  BridgeOutput out;
  auto it = clients_.find(client);
  if (it == clients_.end()) return out;
  Client& c = it->second;
  ClientText message;
  try {
    message = ParseClientText(text);
  } catch (const FoxgloveProtocolError& e) {
    ++counts_.malformed;
    if (std::string_view(e.what()).rfind("unknown op", 0) == 0) {
      ++counts_.unknown_op;
    }
    Refuse(client, c, e.what(), out);
    return out;
  }
  switch (message.kind) {
    case ClientText::Kind::kSubscribe:
      for (const Subscription& s : message.subscriptions) {
        std::string why;
        if (s.channel_id == 0 || s.channel_id > channels_.size()) {
          why = "subscribe: no channel " + std::to_string(s.channel_id);
        } else if (c.channel_of.count(s.id) != 0) {
          why = "subscribe: subscription id " + std::to_string(s.id) +
                " is in use";
        } else if (c.sub_of.count(s.channel_id) != 0) {
          why = "subscribe: already subscribed to channel " +
                std::to_string(s.channel_id);
        } else if (c.channel_of.size() >= options_.max_subscriptions) {
          why = "subscribe: at most " +
                std::to_string(options_.max_subscriptions) +
                " subscriptions per client";
        }
        if (!why.empty()) {
          ++counts_.refused_subscriptions;
          Refuse(client, c, why, out);
          if (c.refusals >= options_.max_refusals) return out;
          continue;
        }
        c.channel_of[s.id] = s.channel_id;
        c.sub_of[s.channel_id] = s.id;
        if (s.channel_id == kSceneChannel) {
          out.send.push_back(
              {client, true, false,
               MessageDataFrame(s.id, timeline_ns_,
                                scene_.SceneUpdateJson(timeline_ns_))});
        }
      }
      break;
    case ClientText::Kind::kUnsubscribe:
      for (const uint32_t id : message.subscription_ids) {
        const auto sub = c.channel_of.find(id);
        if (sub == c.channel_of.end()) continue;  // the spec allows it
        c.sub_of.erase(sub->second);
        c.channel_of.erase(sub);
      }
      break;
    case ClientText::Kind::kUnsupported:
      ++counts_.unsupported;
      Refuse(client, c,
             "op \"" + message.op + "\" is not offered by this server", out);
      break;
  }
  (void)now_ns;
  return out;
}

BridgeOutput FoxgloveBridge::OnClientBinary(ClientId client,
                                            std::string_view data,
                                            uint64_t now_ns) {
  BridgeOutput out;
  auto it = clients_.find(client);
  if (it == clients_.end()) return out;
  CallService(client, it->second, data, now_ns, out);
  return out;
}

void FoxgloveBridge::Fail(ClientId client, uint32_t service_id,
                          uint32_t call_id, const std::string& message,
                          BridgeOutput& out) {
  out.send.push_back(
      {client, false, false,
       Json{{"op", "serviceCallFailure"},
            {"serviceId", service_id},
            {"callId", call_id},
            {"message", message}}
           .dump(-1, ' ', false, Json::error_handler_t::replace)});
}

void FoxgloveBridge::CallService(ClientId client, Client& c,
                                 std::string_view data, uint64_t now_ns,
                                 BridgeOutput& out) {
  ServiceCall call;
  try {
    call = ParseClientBinary(data);
  } catch (const FoxgloveProtocolError& e) {
    ++counts_.malformed;
    Refuse(client, c, e.what(), out);
    return;
  }
  const Service* service = FindService(call.service_id);
  std::string why;
  if (service == nullptr) {
    why = "no service " + std::to_string(call.service_id);
  } else if (!c.may_control) {
    why = std::string(service->name) +
          ": refused: this client may not control the simulator (connect "
          "from this host, or with ?token= of mrsim-foxglove's "
          "--control-key)";
  } else if (call.encoding != "json") {
    why = std::string(service->name) + ": encoding \"" +
          call.encoding.substr(0, 32) + "\": only json is taken";
  } else if (pending_.size() >= kMaxPendingCalls) {
    why = std::string(service->name) + ": " + std::to_string(kMaxPendingCalls) +
          " calls wait for the simulator already";
  }
  sim_control_t control{};
  if (why.empty()) {
    try {
      control = ParseSimControl(Words(*service, call.payload));
    } catch (const std::invalid_argument& e) {
      why = std::string(service->name) + ": " + e.what();
    }
  }
  if (!why.empty()) {
    ++counts_.refused_calls;
    ++c.refusals;
    Fail(client, call.service_id, call.call_id, why, out);
    if (c.refusals == options_.max_refusals) {
      ++counts_.closed;
      out.close.push_back(client);
    }
    return;
  }
  control.utime = static_cast<int64_t>(now_ns / 1000);
  control.seq = next_control_seq_++;
  control.sender = options_.name;
  out.controls.push_back(control);
  pending_.push_back(
      {client, call.service_id, call.call_id, control.seq,
       now_ns + static_cast<uint64_t>(options_.service_timeout_ns)});
}

BridgeOutput FoxgloveBridge::Tick(uint64_t now_ns) {
  BridgeOutput out;
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (now_ns >= it->deadline_ns) {
      Fail(it->client, it->service_id, it->call_id,
           "no answer from the simulator on " +
               SimStatusChannel(options_.prefix) + " in time",
           out);
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

bool FoxgloveBridge::AnySubscriber(uint32_t channel) const {
  for (const auto& [id, c] : clients_) {
    if (c.sub_of.count(channel) != 0) return true;
  }
  return false;
}

void FoxgloveBridge::SendToSubscribers(uint32_t channel,
                                       std::string_view payload,
                                       uint64_t time_ns, bool droppable,
                                       BridgeOutput& out) {
  for (const auto& [id, c] : clients_) {
    const auto sub = c.sub_of.find(channel);
    if (sub == c.sub_of.end()) continue;
    out.send.push_back(
        {id, true, droppable, MessageDataFrame(sub->second, time_ns, payload)});
  }
}

void FoxgloveBridge::AdvanceTime(int64_t utime, BridgeOutput& out) {
  const int64_t sim_ns = utime * 1000;
  if (last_sim_ns_ >= 0 && sim_ns < last_sim_ns_) {
    // A reset or an older checkpoint: the timeline goes on from here.
    offset_ns_ =
        timeline_ns_ - static_cast<uint64_t>(std::max<int64_t>(sim_ns, 0));
  }
  last_sim_ns_ = sim_ns;
  const uint64_t t =
      static_cast<uint64_t>(std::max<int64_t>(sim_ns, 0)) + offset_ns_;
  if (t < timeline_ns_ || (time_sent_ && t == timeline_ns_)) return;
  timeline_ns_ = t;
  time_sent_ = true;
  for (const auto& [id, c] : clients_) {
    out.send.push_back({id, true, true, TimeFrame(timeline_ns_)});
  }
}

FoxgloveBridge::Channel* FoxgloveBridge::ChannelFor(const std::string& topic,
                                                    const MessageJsonType* type,
                                                    BridgeOutput& out) {
  const auto known = channel_of_topic_.find(topic);
  if (known != channel_of_topic_.end()) {
    Channel& ch = channels_[known->second - 1];
    return ch.type == type ? &ch : nullptr;
  }
  const bool camera = type->fingerprint == camera_image_t::getHash();
  return NewChannel(
      {0, topic, type->name,
       camera ? CameraImageWithoutBytesSchema() : type->schema, type},
      out);
}

FoxgloveBridge::Channel* FoxgloveBridge::NewChannel(Channel channel,
                                                    BridgeOutput& out) {
  if (channels_.size() >= options_.max_channels) {
    ++counts_.channels_over_limit;
    return nullptr;
  }
  channel.id = static_cast<uint32_t>(channels_.size() + 1);
  channel_of_topic_[channel.topic] = channel.id;
  channels_.push_back(std::move(channel));
  const std::string advertise = AdvertiseJson({&channels_.back()});
  for (const auto& [client, c] : clients_) {
    out.send.push_back({client, false, false, advertise});
  }
  return &channels_.back();
}

void FoxgloveBridge::OnCameraImage(const std::string& channel,
                                   const MessageJsonType* type,
                                   const void* data, size_t size,
                                   BridgeOutput& out) {
  camera_image_t msg;
  if (!DecodeMessage(data, size, &msg)) {
    ++counts_.lcm_malformed;
    return;
  }
  try {
    DecodeCameraImage(msg);
  } catch (const std::invalid_argument&) {
    ++counts_.lcm_malformed;
    return;
  }
  // A camera keeps its channel: a picture of the other encoding on it (a
  // camera restarted with other settings) is dropped, as Foxglove could
  // not read it with the advertised schema.
  const std::string topic =
      "/camera/" + msg.robot + "/" + std::to_string(msg.camera);
  const char* schema_name = FoxgloveImageSchemaName(msg);
  Channel* image = nullptr;
  const auto known = channel_of_topic_.find(topic);
  if (known == channel_of_topic_.end()) {
    image = NewChannel(
        {0, topic, schema_name, FoxgloveImageSchema(msg), nullptr}, out);
  } else if (channels_[known->second - 1].schema_name == schema_name) {
    image = &channels_[known->second - 1];
  }
  if (image != nullptr && AnySubscriber(image->id)) {
    // The picture's sim time on the protocol's timeline (the same as sim
    // time until a reset), so it lines up with /mrsim/tf.
    constexpr int64_t kMaxUtime = INT64_MAX / 1000;
    const int64_t utime = std::clamp<int64_t>(msg.utime, 0, kMaxUtime);
    json_.Clear();
    WriteFoxgloveImageJson(
        msg, static_cast<uint64_t>(utime) * 1000 + offset_ns_, json_);
    SendToSubscribers(image->id, json_.view(), timeline_ns_, true, out);
  }
  Channel* ch = ChannelFor(channel, type, out);
  if (ch == nullptr || !AnySubscriber(ch->id)) return;
  json_.Clear();
  WriteCameraImageWithoutBytes(msg, json_);
  SendToSubscribers(ch->id, json_.view(), timeline_ns_, true, out);
}

BridgeOutput FoxgloveBridge::OnLcm(const std::string& channel, const void* data,
                                   size_t size, uint64_t /*now_ns*/) {
  BridgeOutput out;
  const MessageJsonType* type = FindMessageJsonType(Fingerprint(data, size));
  if (type == nullptr) {
    ++counts_.lcm_unknown;
    return out;
  }
  if (type->fingerprint == robot_state_t::getHash()) {
    robot_state_t state;
    if (!DecodeMessage(data, size, &state)) {
      ++counts_.lcm_malformed;
      return out;
    }
    AdvanceTime(state.utime, out);
    if (scene_.OnRobotState(state)) {
      SendToSubscribers(kSceneChannel, scene_.SceneUpdateJson(timeline_ns_),
                        timeline_ns_, false, out);
    }
    if (AnySubscriber(kTransformsChannel)) {
      SendToSubscribers(kTransformsChannel,
                        scene_.FrameTransformsJson(state, timeline_ns_),
                        timeline_ns_, true, out);
    }
  } else if (type->fingerprint == scene_state_t::getHash()) {
    scene_state_t state;
    if (!DecodeMessage(data, size, &state)) {
      ++counts_.lcm_malformed;
      return out;
    }
    AdvanceTime(state.utime, out);
    if (scene_.OnSceneState(state)) {
      SendToSubscribers(kSceneChannel, scene_.SceneUpdateJson(timeline_ns_),
                        timeline_ns_, false, out);
    }
    if (AnySubscriber(kTransformsChannel)) {
      SendToSubscribers(kTransformsChannel,
                        scene_.FrameTransformsJson(state, timeline_ns_),
                        timeline_ns_, true, out);
    }
  } else if (type->fingerprint == camera_image_t::getHash()) {
    OnCameraImage(channel, type, data, size, out);
    return out;
  } else if (type->fingerprint == sim_status_t::getHash() &&
             !pending_.empty()) {
    sim_status_t status;
    if (DecodeMessage(data, size, &status) &&
        status.control_sender == options_.name) {
      for (auto it = pending_.begin(); it != pending_.end(); ++it) {
        if (it->seq != status.control_seq) continue;
        const std::string response =
            Json{{"ok", status.control_ok != 0},
                 {"message", status.control_ok ? "" : status.last_error}}
                .dump(-1, ' ', false, Json::error_handler_t::replace);
        out.send.push_back(
            {it->client, true, false,
             ServiceCallResponseFrame(it->service_id, it->call_id, "json",
                                      response)});
        pending_.erase(it);
        break;
      }
    }
  }
  Channel* ch = ChannelFor(channel, type, out);
  if (ch == nullptr || !AnySubscriber(ch->id)) return out;
  json_.Clear();
  if (!type->to_json(data, size, json_, nullptr)) {
    ++counts_.lcm_malformed;
    return out;
  }
  SendToSubscribers(ch->id, json_.view(), timeline_ns_, true, out);
  return out;
}

}  // namespace mrsim::foxglove
