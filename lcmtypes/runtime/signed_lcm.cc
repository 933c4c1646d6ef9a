#include "lcmtypes/runtime/signed_lcm.h"

#include <algorithm>

#include "common/wall_time.h"

namespace mrsim {
namespace {

bool PowerOfTen(std::int64_t n) {
  while (n >= 10 && n % 10 == 0) n /= 10;
  return n == 1;
}

const char* Hint(MessageAuth::Verdict v) {
  switch (v) {
    case MessageAuth::Verdict::kUnsigned:
      return "sent without a key";
    case MessageAuth::Verdict::kForged:
      return "a wrong key or altered on the way";
    case MessageAuth::Verdict::kReplayed:
      return "an old timestamp: a replay, or clocks apart by over 60 s; "
             "--accept-replays takes lcm-logplayer's";
    default:
      return "";
  }
}

}  // namespace

SignedLcm::SignedLcm(const std::string& url, AuthConfig auth, Warn warn)
    : lcm_(url), config_(std::move(auth)), warn_(std::move(warn)) {
  if (config_.enabled()) {
    auth_ = std::make_unique<MessageAuth>(config_.key, config_.accept_replays);
  }
}

SignedLcm::~SignedLcm() {
  for (Entry& e : entries_) {
    if (e.subscription != nullptr) lcm_.unsubscribe(e.subscription);
  }
}

int SignedLcm::publish(const std::string& channel, const void* data,
                       unsigned size) {
  if (!auth_) return lcm_.publish(channel, data, size);
  // One lock over stamping and sending: two threads cannot put a later
  // stamp on the wire first (the receiver would take the earlier one for
  // a replay).
  std::lock_guard<std::mutex> lock(publish_mutex_);
  auth_->Sign(channel, data, size, WallMicros(), &signed_);
  return lcm_.publish(channel, signed_.data(),
                      static_cast<unsigned>(signed_.size()));
}

lcm::Subscription* SignedLcm::Subscribe(const std::string& channel,
                                        RawHandler handler) {
  entries_.push_back(Entry{this, std::move(handler)});
  Entry& entry = entries_.back();
  entry.subscription = lcm_.subscribe(channel, &Entry::On, &entry);
  if (entry.subscription == nullptr) {
    entries_.pop_back();
    return nullptr;
  }
  return entry.subscription;
}

int SignedLcm::unsubscribe(lcm::Subscription* subscription) {
  const auto it = std::find_if(
      entries_.begin(), entries_.end(),
      [&](const Entry& e) { return e.subscription == subscription; });
  if (it == entries_.end()) return -1;
  const int status = lcm_.unsubscribe(subscription);
  entries_.erase(it);
  return status;
}

void SignedLcm::Entry::On(const lcm::ReceiveBuffer* rbuf,
                          const std::string& channel) {
  if (!self->auth_) {
    handler(rbuf, channel);
    return;
  }
  std::size_t payload = 0;
  const MessageAuth::Verdict verdict = self->auth_->Verify(
      channel, rbuf->data, rbuf->data_size, WallMicros(), &payload);
  if (verdict != MessageAuth::Verdict::kOk) {
    self->Refused(verdict, channel);
    return;
  }
  lcm::ReceiveBuffer stripped = *rbuf;
  stripped.data_size = static_cast<uint32_t>(payload);
  handler(&stripped, channel);
}

void SignedLcm::Refused(MessageAuth::Verdict verdict,
                        const std::string& channel) {
  if (!warn_) return;
  const MessageAuth::Counts c = auth_->counts();
  const std::int64_t n =
      verdict == MessageAuth::Verdict::kUnsigned ? c.unsigned_
      : verdict == MessageAuth::Verdict::kForged ? c.forged
                                                 : c.replayed;
  const std::string kind = MessageAuth::ToString(verdict);
  if (warned_.size() < kWarnChannels &&
      warned_.emplace(static_cast<int>(verdict), channel).second) {
    warn_(std::string("dropped ") +
          (verdict == MessageAuth::Verdict::kUnsigned ? "an " : "a ") + kind +
          " message on " + channel + " (" + Hint(verdict) +
          "); more are counted");
  } else if (n >= 10 && PowerOfTen(n)) {
    warn_("dropped " + std::to_string(n) + " " + kind + " messages so far");
  }
}

MessageAuth::Counts SignedLcm::counts() const {
  return auth_ ? auth_->counts() : MessageAuth::Counts{};
}

std::string SignedLcm::Describe() const {
  if (!auth_) return "messages unsigned (no key)";
  return "messages signed with " + config_.key_file +
         (config_.accept_replays ? " (replays accepted)" : "");
}

}  // namespace mrsim
