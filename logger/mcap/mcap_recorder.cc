#include "logger/mcap/mcap_recorder.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "logger/mcap/lcm_protobuf_schema.h"

namespace mrsim {
McapRecorder::McapRecorder(McapRecorderOptions options)
    : options_(std::move(options)) {
  if (!options_.report) options_.report = [](const std::string&) {};
  if (options_.encoding == McapEncoding::kProtobuf) {
    registry_ = LcmTypeRegistry::WithBuiltinTypes();
  }
  mcap::McapWriterOptions writer_options;
  writer_options.library = "mrsim-log";
  writer_options.chunk_size = options_.chunk_size;
  writer_options.compression = options_.compression;
  const std::filesystem::path parent =
      std::filesystem::path(options_.path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  writer_ = std::make_unique<mcap::McapWriter>(options_.path, writer_options);
}

McapRecorder::~McapRecorder() = default;

void McapRecorder::OnMessage(const std::string& channel, const void* data,
                             size_t size, uint64_t log_time_ns) {
  ++messages_;
  auto it = channels_.find(channel);
  if (it == channels_.end()) {
    if (channels_.size() >= kMaxChannels) {
      if (extra_channel_messages_++ == 0) {
        options_.report(channel + ": more than " +
                        std::to_string(kMaxChannels) +
                        " channels; messages on further channels are counted "
                        "and dropped");
      }
      return;
    }
    it = channels_
             .emplace(channel, Channel(ChannelLedger(channel, options_.report)))
             .first;
    it->second.ledger.stats().files.push_back(options_.path);
  }
  Channel& ch = it->second;
  ++ch.ledger.stats().messages;
  if (failed()) return;
  // LCM's receive times can go back a few ms (its first datagrams); a
  // file's log times do not, so readers play it in the order heard.
  if (log_time_ns < last_time_) log_time_ns = last_time_;
  last_time_ = log_time_ns;
  try {
    Record(ch, static_cast<const uint8_t*>(data), size, log_time_ns);
  } catch (const std::exception& e) {
    error_ = e.what();
  }
}

void McapRecorder::Record(Channel& ch, const uint8_t* data, size_t size,
                          uint64_t time) {
  ChannelLedger& ledger = ch.ledger;
  ChannelStats& stats = ledger.stats();
  if (!ledger.CheckSize(size)) return;
  const int64_t hash = LcmFingerprint(data);
  const bool protobuf = options_.encoding == McapEncoding::kProtobuf;
  if (ch.type == nullptr && ch.encoder == nullptr) {
    if (!StartChannel(ch, hash)) {
      ledger.UnknownType(hash);
      return;
    }
  } else if (hash !=
             (protobuf ? ch.encoder->fingerprint() : ch.type->fingerprint)) {
    ledger.OtherType(hash);
    return;
  }
  int64_t seq = 0;
  bool has_seq = false;
  std::string_view text;
  if (protobuf) {
    if (!ch.encoder->Encode(data, size)) {
      ledger.Malformed(size);
      return;
    }
    text = ch.encoder->view();
    has_seq = ch.encoder->has_seq();
    seq = ch.encoder->seq();
  } else {
    json_.Clear();
    if (!ch.type->to_json(data, size, json_, &seq)) {
      ledger.Malformed(size);
      return;
    }
    text = json_.view();
    has_seq = ch.type->has_seq;
  }
  // The re-send check keeps and compares the LCM bytes: the payload is
  // made from them (the JSON is about 2.4 times their size to copy).
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  if (has_seq && !ledger.TakeSeq(seq, bytes)) return;
  // MCAP's sequence is 32 bits: the message's own seq, cut to them.
  const auto sequence = has_seq ? static_cast<uint32_t>(seq) : ch.count;
  ++ch.count;
  writer_->WriteMessage(ch.id, sequence, time, time, text);
  ++stats.rows;
  if (has_seq) ledger.Remember(seq, bytes);
  if (writer_->chunk_messages() > 0 &&
      time - writer_->chunk_start_time() >= options_.chunk_period_ns &&
      time > writer_->chunk_start_time()) {
    writer_->CloseChunk();
  }
}

bool McapRecorder::StartChannel(Channel& ch, int64_t hash) {
  ChannelStats& stats = ch.ledger.stats();
  auto schema = schema_of_type_.find(hash);
  if (options_.encoding == McapEncoding::kJson) {
    ch.type = FindMessageJsonType(hash);
    if (ch.type == nullptr) return false;
    stats.type = ch.type->name;
    if (schema == schema_of_type_.end()) {
      schema =
          schema_of_type_
              .emplace(hash, writer_->AddSchema(ch.type->name, "jsonschema",
                                                ch.type->schema))
              .first;
    }
    ch.id = writer_->AddChannel(schema->second, stats.channel, "json");
    return true;
  }
  const LcmStruct* type = registry_.FindByHash(hash);
  if (type == nullptr) return false;
  auto& encoder = encoders_[hash];
  if (encoder == nullptr) {
    encoder = std::make_unique<LcmProtobufEncoder>(registry_, *type);
  }
  ch.encoder = encoder.get();
  stats.type = type->full_name();
  if (schema == schema_of_type_.end()) {
    schema = schema_of_type_
                 .emplace(hash, writer_->AddSchema(
                                    type->full_name(), "protobuf",
                                    LcmProtobufDescriptorSet(registry_, *type)))
                 .first;
  }
  ch.id = writer_->AddChannel(schema->second, stats.channel, "protobuf");
  return true;
}

void McapRecorder::Tick(uint64_t now_ns) {
  if (failed() || writer_->chunk_messages() == 0) return;
  if (now_ns < writer_->chunk_start_time() + options_.chunk_period_ns) return;
  try {
    writer_->CloseChunk();
  } catch (const std::exception& e) {
    error_ = e.what();
  }
}

void McapRecorder::Finish() {
  try {
    writer_->Finish();
  } catch (const std::exception& e) {
    if (error_.empty()) error_ = e.what();
    throw;
  }
}

std::vector<ChannelStats> McapRecorder::Stats() const {
  std::vector<ChannelStats> out;
  for (const auto& [name, ch] : channels_) {
    out.push_back(ch.ledger.Stats());
  }
  return out;
}

std::string McapRecorder::Summary() const {
  std::ostringstream os;
  int64_t missing = 0;
  os << ChannelSummaryLines(Stats(), "written", &missing);
  os << "  total: " << messages_ << " messages on " << channels_.size()
     << " channels, " << missing << " missing by seq, " << writer_->messages()
     << " in " << writer_->chunks() << " chunks of " << options_.path;
  if (extra_channel_messages_ > 0) {
    os << ", " << extra_channel_messages_ << " on channels over "
       << kMaxChannels << " dropped";
  }
  return os.str();
}

}  // namespace mrsim
