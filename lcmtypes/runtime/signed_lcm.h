// An LCM connection that signs what it publishes and checks what it
// receives when it has a key (MessageAuth), and is plain LCM without one.
// Every mrsim program talks through one, so no handler needs code of its
// own: a handler is called only for messages that passed, with the
// signature trailer already cut off; unsigned, forged and replayed ones are
// counted and reported through `warn`. Same calls as lcm::LCM's for what
// mrsim uses (raw subscriptions, raw and typed publish).
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <list>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lcmtypes/runtime/message_auth.h"
#include "lcmtypes/runtime/message_key.h"

namespace mrsim {

class SignedLcm {
 public:
  using Warn = std::function<void(const std::string&)>;
  using RawHandler =
      std::function<void(const lcm::ReceiveBuffer*, const std::string&)>;
  static constexpr std::size_t kWarnChannels = 64;

  // Opens `url` (empty: LCM's default). Without a key in `auth`, nothing is
  // signed or refused. `warn` (may be empty) gets a line for the first
  // rejected message of each kind on each channel (the first kWarnChannels
  // channels), and for each kind's total at every power of ten.
  explicit SignedLcm(const std::string& url, AuthConfig auth = {},
                     Warn warn = {});
  ~SignedLcm();
  SignedLcm(const SignedLcm&) = delete;
  SignedLcm& operator=(const SignedLcm&) = delete;

  bool good() const { return lcm_.good(); }
  int getFileno() { return lcm_.getFileno(); }
  int handle() { return lcm_.handle(); }
  bool signing() const { return auth_ != nullptr; }

  // Thread-safe; messages leave in the order of the calls.
  int publish(const std::string& channel, const void* data, unsigned size);
  template <class Message>
  int publish(const std::string& channel, const Message* msg) {
    std::vector<std::uint8_t> buffer(msg->getEncodedSize());
    if (msg->encode(buffer.data(), 0, static_cast<int>(buffer.size())) < 0) {
      return -1;
    }
    return publish(channel, buffer.data(),
                   static_cast<unsigned>(buffer.size()));
  }

  template <class Handler>
  lcm::Subscription* subscribe(
      const std::string& channel,
      void (Handler::*method)(const lcm::ReceiveBuffer*, const std::string&),
      Handler* handler) {
    return Subscribe(channel, [handler, method](const lcm::ReceiveBuffer* b,
                                                const std::string& c) {
      (handler->*method)(b, c);
    });
  }
  template <class Context>
  lcm::Subscription* subscribeFunction(const std::string& channel,
                                       void (*fn)(const lcm::ReceiveBuffer*,
                                                  const std::string&, Context),
                                       Context context) {
    return Subscribe(
        channel, [fn, context](const lcm::ReceiveBuffer* b,
                               const std::string& c) { fn(b, c, context); });
  }
  lcm::Subscription* Subscribe(const std::string& channel, RawHandler handler);
  int unsubscribe(lcm::Subscription* subscription);

  // Messages refused so far, by kind (all zero without a key).
  MessageAuth::Counts counts() const;
  // "signed with KEYFILE" / "unsigned (no key)", for start-up lines.
  std::string Describe() const;

 private:
  struct Entry {
    SignedLcm* self;
    RawHandler handler;
    lcm::Subscription* subscription = nullptr;
    void On(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  };
  void Refused(MessageAuth::Verdict verdict, const std::string& channel);

  lcm::LCM lcm_;
  AuthConfig config_;
  std::unique_ptr<MessageAuth> auth_;
  Warn warn_;
  std::mutex publish_mutex_;
  std::vector<std::uint8_t> signed_;  // reused: no allocation per message
  std::list<Entry> entries_;
  std::set<std::pair<int, std::string>> warned_;  // (verdict, channel)
};

}  // namespace mrsim
