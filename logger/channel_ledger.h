// The per-channel accounting both loggers share (Recorder writes CSV,
// McapRecorder MCAP): the counts of ChannelStats, the seq tracker and its
// gap / jump / went-back warnings, the re-send window and the cap on
// warnings. One implementation, so a run logged both ways counts the same
// messages, gaps and re-sends, in the same words.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "logger/channel_stats.h"
#include "logger/seq_tracker.h"

namespace mrsim {

// The type fingerprint an LCM message starts with (its first 8 bytes, big
// endian); data must hold at least 8 bytes.
int64_t LcmFingerprint(const uint8_t* data);

class ChannelLedger {
 public:
  using ReportFn = std::function<void(const std::string&)>;

  // Warnings per channel before further ones are only counted.
  static constexpr int kMaxReports = 50;
  // Messages remembered for the re-send check. A pipelined lockstep
  // simulator re-sends the states it awaits (up to actuation delay + 1) and
  // its controllers re-answer them; eight covers every delay mrsim-sim
  // takes.
  static constexpr size_t kRecentMessages = 8;

  // report receives the warnings (at most kMaxReports, then one saying the
  // rest are only counted); it must be callable.
  ChannelLedger(std::string channel, ReportFn report);

  ChannelStats& stats() { return stats_; }
  const ChannelStats& stats() const { return stats_; }
  // stats() with the seq counts (gaps, missing, jumps back, first, last).
  ChannelStats Stats() const;

  // False (counted as malformed and reported) when size cannot hold an LCM
  // fingerprint.
  bool CheckSize(size_t size);
  // Counted; the first one on the channel is reported.
  void UnknownType(int64_t fingerprint);
  void OtherType(int64_t fingerprint);
  // Counted and reported: size bytes of stats().type that do not decode
  // (`why`, when given, says which field was wrong).
  void Malformed(size_t size, const std::string& why = "");

  // A message of seq whose content (the text written for it) is `content`:
  // false when it is a re-send of one just written (same seq, same
  // content), which is counted, not written; otherwise the seq is tracked
  // and its gaps, jumps and steps back reported, and the caller writes it,
  // then calls Remember.
  // `sender`: the message's own sender field, when its type has one. Each
  // sender's seq is followed on its own (at most kMaxSenders per channel;
  // the rest share the first's), so two senders numbering their messages
  // independently on one channel are no gaps or jumps back.
  bool TakeSeq(int64_t seq, std::string_view content,
               std::string_view sender = {});
  static constexpr size_t kMaxSenders = 16;
  // Keeps the written message for the re-send check: copied into a
  // buffer of the window, or swapped with *content (which then holds an
  // evicted message's buffer, for the next one).
  void Remember(int64_t seq, std::string_view content);
  void Remember(int64_t seq, std::string* content);

  // For a stream whose seq steps by more than one by design (a camera
  // pictures every few states, each picture carrying its state's seq):
  // only the seq range is tracked, and the caller, which knows the
  // stream's period, tells how many messages it found missing just before
  // this one (counted as one gap, reported with `gap_text`).
  void TakeSparseSeq(int64_t seq, int64_t missing, const std::string& gap_text);

  void Report(const std::string& text);

 private:
  std::pair<int64_t, std::string>& NextSlot();

  ChannelStats stats_;
  ReportFn report_;
  SeqTracker seq_;  // the first sender's (or that of a type without one)
  std::string first_sender_;
  bool have_first_sender_ = false;
  std::map<std::string, SeqTracker, std::less<>> other_senders_;
  int reports_ = 0;
  // The last messages written with their seq, a ring.
  std::vector<std::pair<int64_t, std::string>> recent_;
  size_t recent_next_ = 0;
  // TakeSparseSeq's counts (used when TakeSeq saw nothing).
  int64_t sparse_count_ = 0;
  int64_t sparse_first_ = 0;
  int64_t sparse_last_ = 0;
  int64_t sparse_gaps_ = 0;
  int64_t sparse_missing_ = 0;
};

}  // namespace mrsim
