// Writes every message it is given to one CSV per channel (DIR/<channel>.csv)
// and keeps per-channel counts: messages, rows, malformed and unknown-type
// messages, sequence gaps, and re-sends (the same row under a seq just
// written, as when a lockstep simulator re-sends a state its controller has
// not answered: written once). Live logging and .lcmlog
// replay both feed it, so both give the same bytes. Camera channels
// (camera_image_t) are written as pictures instead: a PNG sequence and an
// index per camera (CameraChannelRecorder).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "logger/camera_channel_recorder.h"
#include "logger/channel_ledger.h"
#include "logger/channel_stats.h"
#include "logger/csv_writer.h"
#include "logger/lcm_type_registry.h"
#include "logger/message_flattener.h"
#include "logger/seq_tracker.h"

namespace mrsim {

// One channel's line of a recorder's summary, the same for the CSV and the
// MCAP logger: "  CH: TYPE, N messages, N <written>, seq A..B, G gaps (M
// missing)...", ending in a newline.
std::string ChannelSummaryLine(const ChannelStats& s, const char* written);
// ChannelSummaryLine of every channel, and (to *missing) the messages
// missing by seq over all of them.
std::string ChannelSummaryLines(const std::vector<ChannelStats>& stats,
                                const char* written, int64_t* missing);

struct RecorderOptions {
  std::string out_dir = ".";
  // Receives warnings (gaps, unknown types, new file parts); unset: none
  // (the library never prints; mrsim-log prints them).
  std::function<void(const std::string&)> report;
};

class Recorder {
 public:
  // Files per channel (<channel>.csv, .part2.csv, ...): a new file starts
  // when the messages' shape changes, and traffic that decodes but changes
  // shape with every message must not become thousands of files.
  static constexpr size_t kMaxPartFiles = 8;
  // Channels recorded; messages on further channels are counted and
  // dropped, so a flood of new channel names cannot exhaust memory.
  static constexpr size_t kMaxChannels = 1000;

  // Creates out_dir if needed and checks it is writable; throws
  // std::runtime_error naming the folder otherwise. `registry` must outlive
  // the recorder.
  Recorder(const LcmTypeRegistry& registry, RecorderOptions options);
  ~Recorder();

  // Records one message. Never throws (LCM calls it from C): a write error
  // is kept in error() and later messages are dropped.
  void OnMessage(const std::string& channel, const void* data, size_t size);
  // Writes what is buffered. Throws std::runtime_error naming the file.
  void Flush();

  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  int64_t messages() const { return messages_; }
  // Messages on channels beyond kMaxChannels (not recorded).
  int64_t messages_on_extra_channels() const { return extra_channel_messages_; }
  std::vector<ChannelStats> Stats() const;
  // A human-readable table of Stats(), one line per channel.
  std::string Summary() const;
  // The first CSV file of a channel, or "" when none was written.
  std::string CsvPath(const std::string& channel) const;
  const std::string& out_dir() const { return options_.out_dir; }

 private:
  struct Channel {
    explicit Channel(ChannelLedger l) : ledger(std::move(l)) {}
    ChannelLedger ledger;
    int64_t hash = 0;
    std::unique_ptr<MessageFlattener> flattener;
    std::unique_ptr<CameraChannelRecorder> camera;  // camera_image_t only
    // One file per shape (its header): a message of a shape seen before
    // goes back to that shape's file, so a channel whose shapes alternate
    // (the camera's answers without joints among a controller's) does not
    // run out of files.
    struct Part {
      std::vector<std::string> columns;
      std::unique_ptr<CsvWriter> writer;
    };
    std::vector<Part> parts;
    size_t current = 0;  // the part of the flattener's shape
    uint64_t shape_version = 0;
    FlatRow row;
  };

  void Record(Channel& ch, const uint8_t* data, size_t size);
  void OpenPart(Channel& ch);
  std::string CameraFolderStem(const std::string& channel);

  const LcmTypeRegistry& registry_;
  RecorderOptions options_;
  std::map<std::string, Channel> channels_;
  std::set<std::string> camera_stems_;  // taken by a camera channel
  std::string error_;
  int64_t messages_ = 0;
  int64_t extra_channel_messages_ = 0;
};

// Where a camera channel's pictures go: camera_<robot>_<camera>/ (the
// robot from <prefix>_CAMERA_<robot>), see docs/logger.md.
std::string CameraFolderStemOf(const std::string& channel);

// A channel name as a file name: characters other than letters, digits,
// '_', '-' and '.' become '_'.
std::string ChannelFileStem(const std::string& channel);

}  // namespace mrsim
