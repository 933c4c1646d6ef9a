// Signs and verifies LCM payloads with a shared key, in the manner of
// MAVLink 2: an HMAC-SHA256 (OpenSSL) over the channel, the payload, the
// sender and a strictly increasing timestamp, truncated to 64 bits, carried
// in a trailer after the payload. lcm-gen's decode reads only what a type
// needs and ignores trailing bytes, so lcm-logger, lcm-spy and programs
// without a key still decode signed traffic. The class does no I/O: the
// caller gives the time, so tests drive it with a fake clock.
//
// Trailer (22 bytes, after the payload, big-endian):
//   sender id (4) | timestamp, us since the Unix epoch (8) | HMAC (8) |
//   magic 'M' (1) | version (1)
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace mrsim {

class MessageAuth {
 public:
  static constexpr std::size_t kTrailerSize = 22;
  static constexpr std::size_t kMacSize = 8;
  static constexpr std::uint8_t kMagic = 'M';
  static constexpr std::uint8_t kVersion = 1;
  // A message from a sender not heard from yet (or not for a while) is
  // taken when its timestamp is within this of the receiver's clock, as
  // MAVLink does: a replay older than this is refused even by a receiver
  // that just started. Hosts' clocks must agree to within it (NTP).
  static constexpr std::int64_t kWindowMicros = 60'000'000;
  // Senders remembered before those silent for longer than the window are
  // forgotten (bounded memory; only key holders add senders).
  static constexpr std::size_t kMaxSenders = 4096;

  enum class Verdict { kOk, kUnsigned, kForged, kReplayed };
  struct Counts {
    std::int64_t accepted = 0;
    std::int64_t unsigned_ = 0;
    std::int64_t forged = 0;
    std::int64_t replayed = 0;
    std::int64_t rejected() const { return unsigned_ + forged + replayed; }
  };

  // `key`: the secret bytes (at least 16). accept_replays: take messages
  // whatever their timestamp (a recorded log played back with
  // lcm-logplayer); unsigned and forged ones are still refused. `sender`:
  // this signer's id (0: a random one).
  MessageAuth(const std::string& key, bool accept_replays = false,
              std::uint32_t sender = 0);
  ~MessageAuth();
  MessageAuth(const MessageAuth&) = delete;
  MessageAuth& operator=(const MessageAuth&) = delete;

  // Writes payload + trailer to `out` (resized), stamped with now_us or,
  // when that is not later than the last stamp, the last stamp + 1.
  // Thread-safe.
  void Sign(const std::string& channel, const void* data, std::size_t size,
            std::int64_t now_us, std::vector<std::uint8_t>* out);
  // Checks a received message. kOk: *payload_size is its size without the
  // trailer. Counts the verdict. Thread-safe.
  Verdict Verify(const std::string& channel, const void* data, std::size_t size,
                 std::int64_t now_us, std::size_t* payload_size);

  // The size of `data` without what looks like a signature trailer (its
  // marker bytes at the end), unchecked; `size` when there is none. For
  // readers without the key that check the payload themselves (mrsim-log
  // reading a signed lcm-logger file).
  static std::size_t SizeWithoutTrailer(const void* data, std::size_t size) {
    const auto* b = static_cast<const std::uint8_t*>(data);
    return size >= kTrailerSize && b[size - 2] == kMagic &&
                   b[size - 1] == kVersion
               ? size - kTrailerSize
               : size;
  }

  Counts counts() const;
  std::uint32_t sender() const { return sender_; }
  bool accept_replays() const { return accept_replays_; }
  static const char* ToString(Verdict v);

 private:
  struct Hmac;  // an OpenSSL HMAC context holding the key
  static void Compute(Hmac& hmac, const std::string& channel,
                      const std::uint8_t* data, std::size_t size,
                      const std::uint8_t* stamp, std::uint8_t* mac);

  std::string key_;
  bool accept_replays_;
  std::uint32_t sender_;
  mutable std::mutex sign_mutex_;
  std::unique_ptr<Hmac> sign_hmac_;
  std::int64_t last_stamp_ = 0;
  mutable std::mutex verify_mutex_;
  std::unique_ptr<Hmac> verify_hmac_;
  std::unordered_map<std::uint32_t, std::int64_t> last_seen_;
  Counts counts_;
};

}  // namespace mrsim
