#include "logger/mcap/mcap_recorder.h"

#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace mrsim {
namespace {

constexpr int kMaxReports = 50;
// As the CSV Recorder: a lockstep simulator re-sends up to delay + 1
// states.
constexpr size_t kRecentMessages = 8;

int64_t Fingerprint(const uint8_t* data) {
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v = (v << 8) | data[k];
  return static_cast<int64_t>(v);
}

std::string Hex(int64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof(buf), "0x%016llx",
                static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

McapRecorder::McapRecorder(McapRecorderOptions options)
    : options_(std::move(options)) {
  if (!options_.report) options_.report = [](const std::string&) {};
  mcap::McapWriterOptions writer_options;
  writer_options.library = "mrsim-log";
  writer_options.chunk_size = options_.chunk_size;
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
    it = channels_.emplace(channel, Channel{}).first;
    it->second.stats.channel = channel;
    it->second.stats.files.push_back(options_.path);
  }
  Channel& ch = it->second;
  ++ch.stats.messages;
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
  if (size < 8) {
    ++ch.stats.malformed;
    Report(ch, ch.stats.channel + ": message of " + std::to_string(size) +
                   " bytes is too short to be LCM; dropped");
    return;
  }
  const int64_t hash = Fingerprint(data);
  if (ch.type == nullptr) {
    ch.type = FindMessageJsonType(hash);
    if (ch.type == nullptr) {
      ++ch.stats.unknown_type;
      if (ch.stats.unknown_type == 1) {
        Report(ch, ch.stats.channel + ": unknown message type (fingerprint " +
                       Hex(hash) + "); its messages are counted and skipped");
      }
      return;
    }
    ch.stats.type = ch.type->name;
    auto schema = schema_of_type_.find(hash);
    if (schema == schema_of_type_.end()) {
      schema =
          schema_of_type_
              .emplace(hash, writer_->AddSchema(ch.type->name, "jsonschema",
                                                ch.type->schema))
              .first;
    }
    ch.id = writer_->AddChannel(schema->second, ch.stats.channel, "json");
  } else if (hash != ch.type->fingerprint) {
    ++ch.stats.other_type;
    if (ch.stats.other_type == 1) {
      Report(ch, ch.stats.channel +
                     ": a message of another type (fingerprint " + Hex(hash) +
                     ") on a " + ch.stats.type +
                     " channel; such messages are counted and skipped");
    }
    return;
  }
  json_.Clear();
  int64_t seq = 0;
  if (!ch.type->to_json(data, size, json_, &seq)) {
    ++ch.stats.malformed;
    Report(ch, ch.stats.channel + ": malformed " + ch.stats.type +
                   " message of " + std::to_string(size) + " bytes; dropped");
    return;
  }
  const std::string_view text = json_.view();
  if (ch.type->has_seq) {
    ch.stats.has_seq = true;
    for (const auto& [s, seen] : ch.recent) {
      if (s == seq && seen == text) {
        ++ch.stats.repeats;
        return;
      }
    }
    const SeqTracker::Event e = ch.seq.Add(seq);
    if (e.missing > 0) {
      Report(ch, ch.stats.channel + ": gap: seq " +
                     std::to_string(e.first_missing) +
                     (e.missing > 1 ? ".." + std::to_string(e.first_missing +
                                                            e.missing - 1)
                                    : "") +
                     " missing (" + std::to_string(e.missing) + " messages)");
    } else if (e.jumped) {
      Report(ch, ch.stats.channel + ": seq jumped from " +
                     std::to_string(e.previous) + " to " + std::to_string(seq) +
                     " (publisher restarted, or a forged number); not "
                     "counted as missing");
    } else if (e.went_back) {
      Report(ch, ch.stats.channel + ": seq went back from " +
                     std::to_string(e.previous) + " to " + std::to_string(seq) +
                     " (publisher restarted?)");
    }
  }
  // MCAP's sequence is 32 bits: the message's own seq, cut to them.
  const auto sequence =
      ch.type->has_seq ? static_cast<uint32_t>(seq) : ch.count;
  ++ch.count;
  writer_->WriteMessage(ch.id, sequence, time, time, text);
  ++ch.stats.rows;
  if (ch.type->has_seq) {
    if (ch.recent.size() < kRecentMessages) {
      ch.recent.emplace_back(seq, std::string(text));
    } else {
      ch.recent[ch.recent_next].first = seq;
      ch.recent[ch.recent_next].second.assign(text.data(), text.size());
      ch.recent_next = (ch.recent_next + 1) % kRecentMessages;
    }
  }
  if (writer_->chunk_messages() > 0 &&
      time - writer_->chunk_start_time() >= options_.chunk_period_ns &&
      time > writer_->chunk_start_time()) {
    writer_->CloseChunk();
  }
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

void McapRecorder::Report(Channel& ch, const std::string& text) {
  ++ch.reports;
  if (ch.reports < kMaxReports) {
    options_.report(text);
  } else if (ch.reports == kMaxReports) {
    options_.report(ch.stats.channel +
                    ": further warnings on this channel are only counted");
  }
}

std::vector<ChannelStats> McapRecorder::Stats() const {
  std::vector<ChannelStats> out;
  for (const auto& [name, ch] : channels_) {
    out.push_back(WithSeqCounts(ch.stats, ch.seq));
  }
  return out;
}

std::string McapRecorder::Summary() const {
  std::ostringstream os;
  int64_t missing = 0;
  for (const ChannelStats& s : Stats()) {
    os << ChannelSummaryLine(s, "written");
    missing += s.missing;
  }
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
