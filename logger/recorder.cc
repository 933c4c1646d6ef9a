#include "logger/recorder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "lcmtypes/runtime/message_auth.h"
#include "logger/generic_flattener.h"
#include "logger/robot_state_flattener.h"

namespace mrsim {
namespace {

// Warnings per channel before further ones are only counted.
constexpr int kMaxReports = 50;
// Rows remembered for the re-send check. A pipelined lockstep simulator
// re-sends the states it awaits (up to actuation delay + 1) and its
// controllers re-answer them; eight covers every delay mrsim-sim takes.
constexpr size_t kRecentRows = 8;

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

std::unique_ptr<MessageFlattener> MakeFlattener(const LcmTypeRegistry& registry,
                                                const LcmStruct& type) {
  if (type.full_name() == "mrsim.robot_state_t") {
    return std::make_unique<RobotStateFlattener>(registry);
  }
  return std::make_unique<GenericFlattener>(registry, type);
}

}  // namespace

std::string ChannelFileStem(const std::string& channel) {
  std::string out = channel;
  for (char& c : out) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                    (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!ok) c = '_';
  }
  if (out.empty() || out == "." || out == "..") out = "_" + out;
  return out;
}

Recorder::Recorder(const LcmTypeRegistry& registry, RecorderOptions options)
    : registry_(registry), options_(std::move(options)) {
  namespace fs = std::filesystem;
  if (!options_.report) options_.report = [](const std::string&) {};
  std::error_code ec;
  fs::create_directories(options_.out_dir, ec);
  if (ec || !fs::is_directory(options_.out_dir)) {
    throw std::runtime_error("cannot create output folder " + options_.out_dir +
                             ": " + (ec ? ec.message() : "not a directory"));
  }
  // Find an unwritable folder now rather than at the first message.
  const std::string probe = options_.out_dir + "/.mrsim-log-probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot write in output folder " +
                             options_.out_dir + ": " + std::strerror(errno));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

Recorder::~Recorder() = default;

void Recorder::OnMessage(const std::string& channel, const void* data,
                         size_t size) {
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
  }
  Channel& ch = it->second;
  ++ch.stats.messages;
  if (failed()) return;
  try {
    Record(ch, static_cast<const uint8_t*>(data), size);
  } catch (const std::exception& e) {
    error_ = e.what();
  }
}

void Recorder::Record(Channel& ch, const uint8_t* data, size_t size) {
  if (size < 8) {
    ++ch.stats.malformed;
    Report(ch, ch.stats.channel + ": message of " + std::to_string(size) +
                   " bytes is too short to be LCM; dropped");
    return;
  }
  const int64_t hash = Fingerprint(data);
  if (!ch.flattener) {
    const LcmStruct* type = registry_.FindByHash(hash);
    if (type == nullptr) {
      ++ch.stats.unknown_type;
      if (ch.stats.unknown_type == 1) {
        Report(ch, ch.stats.channel + ": unknown message type (fingerprint " +
                       Hex(hash) + "); its messages are counted and skipped");
      }
      return;
    }
    ch.hash = hash;
    ch.flattener = MakeFlattener(registry_, *type);
    ch.stats.type = type->full_name();
  } else if (hash != ch.hash) {
    ++ch.stats.other_type;
    if (ch.stats.other_type == 1) {
      Report(ch, ch.stats.channel +
                     ": a message of another type (fingerprint " + Hex(hash) +
                     ") on a " + ch.stats.type +
                     " channel; such messages are counted and skipped");
    }
    return;
  }
  // A message signed by a program with a key (docs/security.md) carries a
  // trailer the type's layout does not: tried without it when it does not
  // read whole.
  if (!ch.flattener->Flatten(data, size, &ch.row) &&
      (MessageAuth::SizeWithoutTrailer(data, size) == size ||
       !ch.flattener->Flatten(data, MessageAuth::SizeWithoutTrailer(data, size),
                              &ch.row))) {
    ++ch.stats.malformed;
    Report(ch, ch.stats.channel + ": malformed " + ch.stats.type +
                   " message of " + std::to_string(size) + " bytes; dropped");
    return;
  }
  if (ch.row.has_seq) {
    ch.stats.has_seq = true;
    if (IsRepeat(ch)) return;
    const SeqTracker::Event e = ch.seq.Add(ch.row.seq);
    if (e.missing > 0) {
      Report(ch, ch.stats.channel + ": gap: seq " +
                     std::to_string(e.first_missing) +
                     (e.missing > 1 ? ".." + std::to_string(e.first_missing +
                                                            e.missing - 1)
                                    : "") +
                     " missing (" + std::to_string(e.missing) + " messages)");
    } else if (e.jumped) {
      Report(ch, ch.stats.channel + ": seq jumped from " +
                     std::to_string(e.previous) + " to " +
                     std::to_string(ch.row.seq) +
                     " (publisher restarted, or a forged number); not "
                     "counted as missing");
    } else if (e.went_back) {
      Report(ch, ch.stats.channel + ": seq went back from " +
                     std::to_string(e.previous) + " to " +
                     std::to_string(ch.row.seq) + " (publisher restarted?)");
    }
  }
  if (!ch.writer || ch.flattener->shape_version() != ch.shape_version) {
    if (ch.stats.files.size() >= kMaxPartFiles &&
        ch.flattener->columns() != ch.part_columns) {
      if (ch.stats.dropped++ == 0) {
        Report(ch, ch.stats.channel + ": message shape changed again after " +
                       std::to_string(kMaxPartFiles) +
                       " files; rows of further shapes are counted and "
                       "dropped");
      }
      return;
    }
    if (ch.stats.files.size() >= kMaxPartFiles) {
      ch.shape_version = ch.flattener->shape_version();  // back to its shape
    } else {
      OpenPart(ch);
    }
  }
  ch.writer->WriteLine(ch.row.values);
  ++ch.stats.rows;
  if (ch.row.has_seq) Remember(ch);
}

bool Recorder::IsRepeat(Channel& ch) {
  // Same seq, same row: the publisher sent it again. A restarted
  // publisher's seq goes back too, but its rows differ (or it went back
  // further than the last few rows), so they are written and reported.
  for (const auto& [seq, values] : ch.recent) {
    if (seq == ch.row.seq && values == ch.row.values) {
      ++ch.stats.repeats;
      return true;
    }
  }
  return false;
}

void Recorder::Remember(Channel& ch) {
  // Swapped, not copied: the flatteners clear the row before they write,
  // so the evicted string's buffer serves the next message.
  if (ch.recent.size() < kRecentRows) {
    ch.recent.emplace_back(ch.row.seq, std::string());
    ch.recent.back().second.swap(ch.row.values);
    return;
  }
  ch.recent[ch.recent_next].first = ch.row.seq;
  ch.recent[ch.recent_next].second.swap(ch.row.values);
  ch.recent_next = (ch.recent_next + 1) % kRecentRows;
}

void Recorder::OpenPart(Channel& ch) {
  if (ch.writer) ch.writer->Flush();
  const size_t part = ch.stats.files.size() + 1;
  std::string path = options_.out_dir + "/" +
                     ChannelFileStem(ch.stats.channel) +
                     (part > 1 ? ".part" + std::to_string(part) : "") + ".csv";
  if (part > 1) {
    Report(ch, ch.stats.channel +
                   ": message shape changed (array lengths); continuing in " +
                   path);
  }
  ch.writer = std::make_unique<CsvWriter>(path);
  ch.stats.files.push_back(path);
  ch.shape_version = ch.flattener->shape_version();
  ch.part_columns = ch.flattener->columns();
  std::string header;
  for (const std::string& name : ch.flattener->columns()) {
    if (!header.empty()) header.push_back(',');
    header += name;
  }
  ch.writer->WriteLine(header);
}

void Recorder::Report(Channel& ch, const std::string& text) {
  ++ch.reports;
  if (ch.reports < kMaxReports) {
    options_.report(text);
  } else if (ch.reports == kMaxReports) {
    options_.report(ch.stats.channel +
                    ": further warnings on this channel are only counted");
  }
}

void Recorder::Flush() {
  std::string first_error;
  for (auto& [name, ch] : channels_) {
    if (!ch.writer || ch.writer->failed()) continue;
    try {
      ch.writer->Flush();
    } catch (const std::exception& e) {
      if (first_error.empty()) first_error = e.what();
    }
  }
  if (!first_error.empty()) {
    if (error_.empty()) error_ = first_error;
    throw std::runtime_error(first_error);
  }
}

ChannelStats WithSeqCounts(ChannelStats stats, const SeqTracker& seq) {
  stats.gaps = seq.gaps();
  stats.missing = seq.missing();
  stats.back_jumps = seq.back_jumps();
  stats.first_seq = seq.first();
  stats.last_seq = seq.last();
  return stats;
}

std::string ChannelSummaryLine(const ChannelStats& s, const char* written) {
  std::ostringstream os;
  os << "  " << s.channel << ": ";
  if (s.type.empty()) {
    os << s.messages << " messages of unknown type, skipped\n";
    return os.str();
  }
  os << s.type << ", " << s.messages << " messages, " << s.rows << " "
     << written;
  if (s.has_seq) {
    os << ", seq " << s.first_seq << ".." << s.last_seq << ", " << s.gaps
       << " gaps (" << s.missing << " missing)";
    if (s.back_jumps > 0) os << ", " << s.back_jumps << " seq jumps back";
    if (s.repeats > 0) os << ", " << s.repeats << " re-sends skipped";
  }
  if (s.malformed > 0) os << ", " << s.malformed << " malformed";
  if (s.dropped > 0) {
    os << ", " << s.dropped << " dropped (over " << Recorder::kMaxPartFiles
       << " files)";
  }
  if (s.unknown_type + s.other_type > 0) {
    os << ", " << (s.unknown_type + s.other_type) << " of another type";
  }
  for (const std::string& f : s.files) os << " -> " << f;
  os << "\n";
  return os.str();
}

std::vector<ChannelStats> Recorder::Stats() const {
  std::vector<ChannelStats> out;
  for (const auto& [name, ch] : channels_) {
    out.push_back(WithSeqCounts(ch.stats, ch.seq));
  }
  return out;
}

std::string Recorder::Summary() const {
  std::ostringstream os;
  int64_t missing = 0;
  for (const ChannelStats& s : Stats()) {
    os << ChannelSummaryLine(s, "rows");
    missing += s.missing;
  }
  os << "  total: " << messages_ << " messages on " << channels_.size()
     << " channels, " << missing << " missing by seq";
  if (extra_channel_messages_ > 0) {
    os << ", " << extra_channel_messages_ << " on channels over "
       << kMaxChannels << " dropped";
  }
  return os.str();
}

std::string Recorder::CsvPath(const std::string& channel) const {
  auto it = channels_.find(channel);
  if (it == channels_.end() || it->second.stats.files.empty()) return "";
  return it->second.stats.files.front();
}

}  // namespace mrsim
