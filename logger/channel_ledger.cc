#include "logger/channel_ledger.h"

#include <algorithm>
#include <cstdio>

namespace mrsim {
namespace {

std::string Hex(int64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof(buf), "0x%016llx",
                static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

int64_t LcmFingerprint(const uint8_t* data) {
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v = (v << 8) | data[k];
  return static_cast<int64_t>(v);
}

ChannelLedger::ChannelLedger(std::string channel, ReportFn report)
    : report_(std::move(report)) {
  stats_.channel = std::move(channel);
}

ChannelStats ChannelLedger::Stats() const {
  ChannelStats s = stats_;
  s.gaps = seq_.gaps();
  s.missing = seq_.missing();
  s.back_jumps = seq_.back_jumps();
  s.first_seq = seq_.first();
  s.last_seq = seq_.last();
  for (const auto& [sender, t] : other_senders_) {
    s.gaps += t.gaps();
    s.missing += t.missing();
    s.back_jumps += t.back_jumps();
    if (seq_.count() == 0) {
      s.first_seq = t.first();
      s.last_seq = t.last();
    }
  }
  if (seq_.count() == 0 && sparse_count_ > 0) {
    s.gaps = sparse_gaps_;
    s.missing = sparse_missing_;
    s.first_seq = sparse_first_;
    s.last_seq = sparse_last_;
  }
  return s;
}

bool ChannelLedger::CheckSize(size_t size) {
  if (size >= 8) return true;
  ++stats_.malformed;
  Report(stats_.channel + ": message of " + std::to_string(size) +
         " bytes is too short to be LCM; dropped");
  return false;
}

void ChannelLedger::UnknownType(int64_t fingerprint) {
  if (++stats_.unknown_type == 1) {
    Report(stats_.channel + ": unknown message type (fingerprint " +
           Hex(fingerprint) + "); its messages are counted and skipped");
  }
}

void ChannelLedger::OtherType(int64_t fingerprint) {
  if (++stats_.other_type == 1) {
    Report(stats_.channel + ": a message of another type (fingerprint " +
           Hex(fingerprint) + ") on a " + stats_.type +
           " channel; such messages are counted and skipped");
  }
}

void ChannelLedger::Malformed(size_t size, const std::string& why) {
  ++stats_.malformed;
  Report(stats_.channel + ": malformed " + stats_.type + " message of " +
         std::to_string(size) + " bytes" +
         (why.empty() ? "" : " (" + why + ")") + "; dropped");
}

void ChannelLedger::TakeSparseSeq(int64_t seq, int64_t missing,
                                  const std::string& gap_text) {
  stats_.has_seq = true;
  if (sparse_count_++ == 0) sparse_first_ = sparse_last_ = seq;
  sparse_first_ = std::min(sparse_first_, seq);
  sparse_last_ = std::max(sparse_last_, seq);
  if (missing > 0) {
    ++sparse_gaps_;
    sparse_missing_ += missing;
    Report(stats_.channel + ": gap: " + gap_text);
  }
}

bool ChannelLedger::TakeSeq(int64_t seq, std::string_view content,
                            std::string_view sender) {
  stats_.has_seq = true;
  // Same seq, same content: the publisher sent it again. A restarted
  // publisher's seq goes back too, but its messages differ (or it went back
  // further than the window), so they are written and reported.
  for (const auto& [s, seen] : recent_) {
    if (s == seq && seen == content) {
      ++stats_.repeats;
      return false;
    }
  }
  if (!have_first_sender_) {
    have_first_sender_ = true;
    first_sender_ = sender;
  }
  SeqTracker* tracker = &seq_;
  std::string who;
  if (sender != first_sender_) {
    auto it = other_senders_.find(sender);
    if (it == other_senders_.end() && other_senders_.size() + 1 < kMaxSenders) {
      it = other_senders_.emplace(std::string(sender), SeqTracker()).first;
    }
    if (it != other_senders_.end()) {
      tracker = &it->second;
      who = " (sender " + std::string(sender) + ")";
    }
  }
  const SeqTracker::Event e = tracker->Add(seq);
  if (e.missing > 0) {
    Report(
        stats_.channel + who + ": gap: seq " + std::to_string(e.first_missing) +
        (e.missing > 1 ? ".." + std::to_string(e.first_missing + e.missing - 1)
                       : "") +
        " missing (" + std::to_string(e.missing) + " messages)");
  } else if (e.jumped) {
    Report(stats_.channel + who + ": seq jumped from " +
           std::to_string(e.previous) + " to " + std::to_string(seq) +
           " (publisher restarted, or a forged number); not counted as "
           "missing");
  } else if (e.went_back) {
    Report(stats_.channel + who + ": seq went back from " +
           std::to_string(e.previous) + " to " + std::to_string(seq) +
           " (publisher restarted?)");
  }
  return true;
}

std::pair<int64_t, std::string>& ChannelLedger::NextSlot() {
  if (recent_.size() < kRecentMessages) return recent_.emplace_back();
  auto& slot = recent_[recent_next_];
  recent_next_ = (recent_next_ + 1) % kRecentMessages;
  return slot;
}

void ChannelLedger::Remember(int64_t seq, std::string_view content) {
  auto& slot = NextSlot();
  slot.first = seq;
  // assign keeps the evicted message's buffer: no allocation once the
  // window is full.
  slot.second.assign(content.data(), content.size());
}

void ChannelLedger::Remember(int64_t seq, std::string* content) {
  auto& slot = NextSlot();
  slot.first = seq;
  slot.second.swap(*content);
}

void ChannelLedger::Report(const std::string& text) {
  ++reports_;
  if (reports_ < kMaxReports) {
    report_(text);
  } else if (reports_ == kMaxReports) {
    report_(stats_.channel +
            ": further warnings on this channel are only counted");
  }
}

}  // namespace mrsim
