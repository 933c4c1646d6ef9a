// What a node core asks its adapter to publish: decoded messages with their
// channels, in order, and the wall clock the cores are given. Cores fill an
// Outbox; the adapter (the only owner of an lcm::LCM) encodes and sends it,
// and tests read it directly, with a fake clock.
#pragma once

#include <chrono>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace mrsim {

// Wall time as the nodes see it. Adapters pass steady_clock::now(); tests
// pass a fake clock of their own.
using WallClock = std::chrono::steady_clock;
using WallTime = WallClock::time_point;

inline WallTime AfterSeconds(WallTime t, double seconds) {
  // Clamped to +-1e9 s (32 years; NaN counts as the past): a time computed
  // from a hostile number (a speed of 1e-300) must not overflow the clock's
  // 64-bit nanoseconds, which is undefined behaviour.
  constexpr double kLimit = 1e9;
  if (!(seconds > -kLimit)) seconds = -kLimit;
  if (seconds > kLimit) seconds = kLimit;
  return t + std::chrono::duration_cast<WallClock::duration>(
                 std::chrono::duration<double>(seconds));
}
inline double SecondsBetween(WallTime from, WallTime to) {
  return std::chrono::duration<double>(to - from).count();
}

template <class... Messages>
struct Outbox {
  using Message = std::variant<Messages...>;
  std::vector<std::pair<std::string, Message>> messages;

  void Add(std::string channel, Message message) {
    messages.emplace_back(std::move(channel), std::move(message));
  }
  bool empty() const { return messages.empty(); }
  void clear() { messages.clear(); }
};

// Encodes and publishes everything in `out` (through one reused buffer, so
// a steady stream allocates nothing), then empties it. `lcm` is an
// lcm::LCM or anything with its publish(channel, data, size), such as a
// PublishThread.
template <class Sender, class... Messages>
void PublishAll(Sender& lcm, Outbox<Messages...>* out,
                std::vector<uint8_t>* buffer) {
  for (const auto& entry : out->messages) {
    // Not a structured binding: C++17 lambdas cannot capture one (clang).
    const std::string& channel = entry.first;
    const auto& message = entry.second;
    std::visit(
        [&](const auto& msg) {
          const int size = msg.getEncodedSize();
          if (buffer->size() < static_cast<size_t>(size)) buffer->resize(size);
          msg.encode(buffer->data(), 0, size);
          lcm.publish(channel, buffer->data(), static_cast<unsigned>(size));
        },
        message);
  }
  out->clear();
}

}  // namespace mrsim
