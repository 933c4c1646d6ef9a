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

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/message_auth.h"
#include "logger/generic_flattener.h"
#include "logger/robot_state_flattener.h"

namespace mrsim {
namespace {

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

std::string CameraFolderStemOf(const std::string& channel) {
  static const std::string kMark = ChannelNamed("camera").infix;
  const size_t at = channel.find(kMark);
  return "camera_" + ChannelFileStem(at == std::string::npos
                                         ? channel
                                         : channel.substr(at + kMark.size()));
}

std::string Recorder::CameraFolderStem(const std::string& channel) {
  // Two prefixes' channels of one robot name (recorded together with
  // --channels) must not write into one folder.
  std::string stem = CameraFolderStemOf(channel);
  if (!camera_stems_.insert(stem).second) {
    stem = "camera_" + ChannelFileStem(channel);
    camera_stems_.insert(stem);
  }
  return stem;
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
    it = channels_
             .emplace(channel, Channel(ChannelLedger(channel, options_.report)))
             .first;
  }
  Channel& ch = it->second;
  ChannelStats& stats = ch.ledger.stats();
  ++stats.messages;
  if (failed()) return;
  try {
    Record(ch, static_cast<const uint8_t*>(data), size);
  } catch (const std::exception& e) {
    error_ = e.what();
  }
}

void Recorder::Record(Channel& ch, const uint8_t* data, size_t size) {
  ChannelLedger& ledger = ch.ledger;
  ChannelStats& stats = ledger.stats();
  if (!ledger.CheckSize(size)) return;
  const int64_t hash = LcmFingerprint(data);
  if (!ch.flattener && !ch.camera) {
    const LcmStruct* type = registry_.FindByHash(hash);
    if (type == nullptr) {
      ledger.UnknownType(hash);
      return;
    }
    ch.hash = hash;
    stats.type = type->full_name();
    if (stats.type == "mrsim.camera_image_t") {
      ch.camera = std::make_unique<CameraChannelRecorder>(
          options_.out_dir, CameraFolderStem(stats.channel));
    } else {
      ch.flattener = MakeFlattener(registry_, *type);
    }
  } else if (hash != ch.hash) {
    ledger.OtherType(hash);
    return;
  }
  if (ch.camera) {
    ch.camera->Record(data, size, ledger);
    return;
  }
  // A message signed by a program with a key (docs/security.md) carries a
  // trailer the type's layout does not: tried without it when it does not
  // read whole.
  if (!ch.flattener->Flatten(data, size, &ch.row) &&
      (MessageAuth::SizeWithoutTrailer(data, size) == size ||
       !ch.flattener->Flatten(data, MessageAuth::SizeWithoutTrailer(data, size),
                              &ch.row))) {
    ledger.Malformed(size);
    return;
  }
  if (ch.row.has_seq &&
      !ledger.TakeSeq(ch.row.seq, ch.row.values, ch.row.sender)) {
    return;
  }
  if (ch.parts.empty() || ch.flattener->shape_version() != ch.shape_version) {
    const std::vector<std::string>& columns = ch.flattener->columns();
    size_t found = 0;
    while (found < ch.parts.size() && ch.parts[found].columns != columns) {
      ++found;
    }
    if (found < ch.parts.size()) {
      ch.current = found;  // back to a shape it had
      ch.shape_version = ch.flattener->shape_version();
    } else if (ch.parts.size() >= kMaxPartFiles) {
      if (stats.dropped++ == 0) {
        ledger.Report(stats.channel + ": message shape changed again after " +
                      std::to_string(kMaxPartFiles) +
                      " files; rows of further shapes are counted and "
                      "dropped");
      }
      return;
    } else {
      OpenPart(ch);
    }
  }
  ch.parts[ch.current].writer->WriteLine(ch.row.values);
  ++stats.rows;
  // Swapped, not copied: the flatteners clear the row before they write,
  // so the evicted string's buffer serves the next message.
  if (ch.row.has_seq) ledger.Remember(ch.row.seq, &ch.row.values);
}

void Recorder::OpenPart(Channel& ch) {
  ChannelStats& stats = ch.ledger.stats();
  const size_t part = stats.files.size() + 1;
  std::string path = options_.out_dir + "/" + ChannelFileStem(stats.channel) +
                     (part > 1 ? ".part" + std::to_string(part) : "") + ".csv";
  if (part > 1) {
    ch.ledger.Report(stats.channel +
                     ": message shape changed (array lengths); messages of "
                     "the new shape go to " +
                     path);
  }
  Channel::Part& p = ch.parts.emplace_back();
  p.writer = std::make_unique<CsvWriter>(path);
  p.columns = ch.flattener->columns();
  stats.files.push_back(path);
  ch.current = ch.parts.size() - 1;
  ch.shape_version = ch.flattener->shape_version();
  std::string header;
  for (const std::string& name : p.columns) {
    if (!header.empty()) header.push_back(',');
    header += name;
  }
  p.writer->WriteLine(header);
}

void Recorder::Flush() {
  std::string first_error;
  for (auto& [name, ch] : channels_) {
    if (ch.camera) {
      try {
        ch.camera->Flush();
      } catch (const std::exception& e) {
        if (first_error.empty()) first_error = e.what();
      }
    }
    for (Channel::Part& p : ch.parts) {
      if (p.writer->failed()) continue;
      try {
        p.writer->Flush();
      } catch (const std::exception& e) {
        if (first_error.empty()) first_error = e.what();
      }
    }
  }
  if (!first_error.empty()) {
    if (error_.empty()) error_ = first_error;
    throw std::runtime_error(first_error);
  }
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

std::string ChannelSummaryLines(const std::vector<ChannelStats>& stats,
                                const char* written, int64_t* missing) {
  std::string out;
  *missing = 0;
  for (const ChannelStats& s : stats) {
    out += ChannelSummaryLine(s, written);
    *missing += s.missing;
  }
  return out;
}

std::vector<ChannelStats> Recorder::Stats() const {
  std::vector<ChannelStats> out;
  for (const auto& [name, ch] : channels_) {
    out.push_back(ch.ledger.Stats());
  }
  return out;
}

std::string Recorder::Summary() const {
  std::ostringstream os;
  int64_t missing = 0;
  os << ChannelSummaryLines(Stats(), "rows", &missing);
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
  if (it == channels_.end()) return "";
  const ChannelStats& stats = it->second.ledger.stats();
  return stats.files.empty() ? "" : stats.files.front();
}

}  // namespace mrsim
