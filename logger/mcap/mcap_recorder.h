// Records LCM messages into one MCAP file: each channel an MCAP channel of
// protobuf messages with their schema made from the type's .lcm
// (LcmProtobufEncoder, lcm_protobuf_schema.h), or of JSON messages with the
// JSON Schema of its type (mrsim/message_json.hpp, decoded with the
// checked decode). It keeps the CSV Recorder's accounting
// (ChannelStats: malformed and unknown-type messages counted and dropped,
// sequence gaps, jumps back, re-sends of the same message under the same
// seq written once), so a run logged both ways gives as many messages as
// rows. Chunks are closed every options.chunk_period of log time (and at
// chunk_size bytes), so a killed logger loses at most that much.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lcmtypes/json/json_writer.h"
#include "logger/channel_ledger.h"
#include "logger/lcm_type_registry.h"
#include "logger/mcap/lcm_protobuf_encoder.h"
#include "logger/mcap/mcap_writer.h"
#include "logger/recorder.h"
#include "mrsim/message_json.hpp"

namespace mrsim {

// How the messages are stored: protobuf (the smaller file, a third of the
// CPU) or JSON (for readers without protobuf).
enum class McapEncoding { kProtobuf, kJson };

struct McapRecorderOptions {
  std::string path;
  // Receives warnings (gaps, unknown types); unset: none.
  std::function<void(const std::string&)> report;
  // A chunk is closed once it holds messages this much older (ns of log
  // time) than the newest, or chunk_size bytes.
  uint64_t chunk_period_ns = 1000000000;
  size_t chunk_size = 1 << 20;
  mcap::ChunkCompression compression = mcap::ChunkCompression::kZstd;
  McapEncoding encoding = McapEncoding::kProtobuf;
};

class McapRecorder {
 public:
  // Channels recorded (as Recorder::kMaxChannels).
  static constexpr size_t kMaxChannels = Recorder::kMaxChannels;

  // Creates the file (and its folder if needed). Throws
  // std::runtime_error naming it.
  explicit McapRecorder(McapRecorderOptions options);
  ~McapRecorder();

  // Records one message received at log_time_ns (ns since the epoch; an
  // earlier time than the previous message's is taken as that one's).
  // Never throws: a write error is kept in error() and later messages are
  // dropped.
  void OnMessage(const std::string& channel, const void* data, size_t size,
                 uint64_t log_time_ns);
  // Closes the open chunk when its first message is chunk_period_ns older
  // than now_ns: a file whose writer is killed is then readable up to a
  // period ago. Never throws (see OnMessage).
  void Tick(uint64_t now_ns);
  // Writes the summary and footer. Throws std::runtime_error naming the
  // file.
  void Finish();

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  int64_t messages() const { return messages_; }
  const std::string& path() const { return options_.path; }
  // Per channel; `rows` are the messages written to the file.
  std::vector<ChannelStats> Stats() const;
  // A human-readable table of Stats(), one line per channel.
  std::string Summary() const;

 private:
  struct Channel {
    explicit Channel(ChannelLedger l) : ledger(std::move(l)) {}
    ChannelLedger ledger;
    const MessageJsonType* type = nullptr;  // JSON
    LcmProtobufEncoder* encoder = nullptr;  // protobuf
    uint16_t id = 0;
    uint32_t count = 0;
  };

  void Record(Channel& ch, const uint8_t* data, size_t size, uint64_t time);
  // Sets up ch's type, schema and MCAP channel from its first message's
  // fingerprint; false when the type is unknown.
  bool StartChannel(Channel& ch, int64_t hash);

  McapRecorderOptions options_;
  std::unique_ptr<mcap::McapWriter> writer_;
  std::map<int64_t, uint16_t> schema_of_type_;
  LcmTypeRegistry registry_;  // protobuf: the types, from their .lcm
  std::map<int64_t, std::unique_ptr<LcmProtobufEncoder>> encoders_;
  std::map<std::string, Channel> channels_;
  JsonWriter json_;
  std::string error_;
  int64_t messages_ = 0;
  int64_t extra_channel_messages_ = 0;
  uint64_t last_time_ = 0;  // log times never go back
};

}  // namespace mrsim
