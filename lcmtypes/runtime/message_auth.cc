#include "lcmtypes/runtime/message_auth.h"

#include <openssl/core_names.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/params.h>
#include <openssl/rand.h>

#include <cstring>
#include <iterator>
#include <stdexcept>

namespace mrsim {
namespace {

constexpr std::size_t kStampSize = 12;  // sender id + timestamp

void PutBig(std::uint64_t v, int bytes, std::uint8_t* out) {
  for (int i = bytes - 1; i >= 0; --i) {
    out[i] = static_cast<std::uint8_t>(v & 0xff);
    v >>= 8;
  }
}

std::uint64_t GetBig(const std::uint8_t* in, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | in[i];
  return v;
}

}  // namespace

// One EVP_MAC context keyed once; re-initialised per message with the same
// key (EVP_MAC_init with a null key), so signing allocates nothing.
struct MessageAuth::Hmac {
  EVP_MAC* mac = nullptr;
  EVP_MAC_CTX* ctx = nullptr;
  explicit Hmac(const std::string& key) {
    mac = EVP_MAC_fetch(nullptr, "HMAC", nullptr);
    if (mac != nullptr) ctx = EVP_MAC_CTX_new(mac);
    char digest[] = "SHA256";
    OSSL_PARAM params[] = {
        OSSL_PARAM_construct_utf8_string(OSSL_MAC_PARAM_DIGEST, digest, 0),
        OSSL_PARAM_construct_end()};
    if (ctx == nullptr ||
        EVP_MAC_init(ctx, reinterpret_cast<const unsigned char*>(key.data()),
                     key.size(), params) != 1) {
      Free();
      throw std::runtime_error("OpenSSL cannot set up HMAC-SHA256");
    }
  }
  ~Hmac() { Free(); }
  void Free() {
    EVP_MAC_CTX_free(ctx);
    EVP_MAC_free(mac);
    ctx = nullptr;
    mac = nullptr;
  }
};

MessageAuth::MessageAuth(const std::string& key, bool accept_replays,
                         std::uint32_t sender)
    : key_(key), accept_replays_(accept_replays), sender_(sender) {
  if (key.size() < 16) {
    throw std::invalid_argument("a message key needs at least 16 bytes");
  }
  while (sender_ == 0) {
    if (RAND_bytes(reinterpret_cast<unsigned char*>(&sender_),
                   sizeof sender_) != 1) {
      throw std::runtime_error("OpenSSL cannot draw a sender id");
    }
  }
  sign_hmac_ = std::make_unique<Hmac>(key_);
  verify_hmac_ = std::make_unique<Hmac>(key_);
}

MessageAuth::~MessageAuth() = default;

void MessageAuth::Compute(Hmac& hmac, const std::string& channel,
                          const std::uint8_t* data, std::size_t size,
                          const std::uint8_t* stamp, std::uint8_t* mac) {
  std::uint8_t head[5];
  head[0] = kVersion;
  PutBig(channel.size(), 4, head + 1);
  unsigned char full[EVP_MAX_MD_SIZE];
  std::size_t full_size = 0;
  if (EVP_MAC_init(hmac.ctx, nullptr, 0, nullptr) != 1 ||
      EVP_MAC_update(hmac.ctx, head, sizeof head) != 1 ||
      EVP_MAC_update(hmac.ctx,
                     reinterpret_cast<const unsigned char*>(channel.data()),
                     channel.size()) != 1 ||
      EVP_MAC_update(hmac.ctx, stamp, kStampSize) != 1 ||
      EVP_MAC_update(hmac.ctx, data, size) != 1 ||
      EVP_MAC_final(hmac.ctx, full, &full_size, sizeof full) != 1 ||
      full_size < kMacSize) {
    throw std::runtime_error("OpenSSL HMAC-SHA256 failed");
  }
  std::memcpy(mac, full, kMacSize);
}

void MessageAuth::Sign(const std::string& channel, const void* data,
                       std::size_t size, std::int64_t now_us,
                       std::vector<std::uint8_t>* out) {
  out->resize(size + kTrailerSize);
  if (size > 0) std::memcpy(out->data(), data, size);
  std::uint8_t* trailer = out->data() + size;
  std::lock_guard<std::mutex> lock(sign_mutex_);
  last_stamp_ = now_us > last_stamp_ ? now_us : last_stamp_ + 1;
  PutBig(sender_, 4, trailer);
  PutBig(static_cast<std::uint64_t>(last_stamp_), 8, trailer + 4);
  Compute(*sign_hmac_, channel, out->data(), size, trailer,
          trailer + kStampSize);
  trailer[kStampSize + kMacSize] = kMagic;
  trailer[kStampSize + kMacSize + 1] = kVersion;
}

MessageAuth::Verdict MessageAuth::Verify(const std::string& channel,
                                         const void* data, std::size_t size,
                                         std::int64_t now_us,
                                         std::size_t* payload_size) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::lock_guard<std::mutex> lock(verify_mutex_);
  if (size < kTrailerSize || bytes[size - 2] != kMagic ||
      bytes[size - 1] != kVersion) {
    ++counts_.unsigned_;
    return Verdict::kUnsigned;
  }
  const std::size_t payload = size - kTrailerSize;
  const std::uint8_t* trailer = bytes + payload;
  std::uint8_t mac[kMacSize];
  Compute(*verify_hmac_, channel, bytes, payload, trailer, mac);
  if (CRYPTO_memcmp(mac, trailer + kStampSize, kMacSize) != 0) {
    ++counts_.forged;
    return Verdict::kForged;
  }
  if (!accept_replays_) {
    const auto sender = static_cast<std::uint32_t>(GetBig(trailer, 4));
    const auto stamp = static_cast<std::int64_t>(GetBig(trailer + 4, 8));
    const auto it = last_seen_.find(sender);
    if (stamp < now_us - kWindowMicros || stamp > now_us + kWindowMicros ||
        (it != last_seen_.end() && stamp <= it->second)) {
      ++counts_.replayed;
      return Verdict::kReplayed;
    }
    if (it != last_seen_.end()) {
      it->second = stamp;
    } else {
      if (last_seen_.size() >= kMaxSenders) {
        // Forgetting a sender whose last stamp left the window lets none
        // of its old messages back in: the window refuses them.
        for (auto s = last_seen_.begin(); s != last_seen_.end();) {
          s = s->second < now_us - kWindowMicros ? last_seen_.erase(s)
                                                 : std::next(s);
        }
      }
      if (last_seen_.size() >= kMaxSenders) {
        ++counts_.replayed;  // cannot tell: refuse rather than forget
        return Verdict::kReplayed;
      }
      last_seen_.emplace(sender, stamp);
    }
  }
  ++counts_.accepted;
  *payload_size = payload;
  return Verdict::kOk;
}

MessageAuth::Counts MessageAuth::counts() const {
  std::lock_guard<std::mutex> lock(verify_mutex_);
  return counts_;
}

const char* MessageAuth::ToString(Verdict v) {
  switch (v) {
    case Verdict::kOk:
      return "signed";
    case Verdict::kUnsigned:
      return "unsigned";
    case Verdict::kForged:
      return "forged";
    case Verdict::kReplayed:
      return "replayed";
  }
  return "?";
}

}  // namespace mrsim
