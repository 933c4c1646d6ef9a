// Decoding a raw LCM buffer. Our handlers subscribe raw rather than typed,
// because lcm-cpp's typed subscriptions drop undecodable messages silently
// and we must count what we drop, and because lcm-gen's decode trusts every
// length it reads: a forged string length reads far past the datagram and a
// forged array length allocates gigabytes. So the bytes are walked by the
// generated bounds check (mrsim/wire_check.hpp) first, and lcm-gen's decode
// only ever sees messages whose lengths it may trust.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>

#include "lcmtypes/runtime/message_auth.h"
#include "mrsim/wire_check.hpp"

namespace mrsim {

// Messages refused by the bounds check in this process (any type), for
// tests and diagnostics; every caller also counts its own drops.
inline std::atomic<int64_t>& WireRejections() {
  static std::atomic<int64_t> count{0};
  return count;
}

// True when `data` holds exactly one well-formed Message (right
// fingerprint, every length within the bytes and its field's maximum), then
// decoded into `msg`. `error` (optional) says which field was refused.
// Never throws and never allocates more than the message's own size.
//
// A message signed by a sender with a key (lcmtypes/runtime/message_auth.h)
// ends with the signature trailer. A receiver with the key has checked and
// removed it before decoding; one without a key (a viewer, lcm-spy) reads
// the message and ignores the trailer, as it reads unsigned traffic.
template <class Message>
bool DecodeMessage(const void* data, size_t size, Message* msg,
                   WireError* error = nullptr) noexcept {
  if (!CheckWire<Message>(data, size, error)) {
    const size_t unsigned_size = MessageAuth::SizeWithoutTrailer(data, size);
    if (unsigned_size == size ||
        !CheckWire<Message>(data, unsigned_size, nullptr)) {
      WireRejections().fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    size = unsigned_size;
    if (error) *error = WireError{};
  }
  try {
    // The check bounds size by the types' maxima, far below INT32_MAX.
    if (msg->decode(data, 0, static_cast<int>(size)) !=
        static_cast<int>(size)) {
      return false;
    }
    ClearEmptyArrays(msg);
    return true;
  } catch (...) {
    return false;  // out of memory: the message is dropped like a bad one
  }
}

template <class Message>
bool DecodeMessage(const lcm::ReceiveBuffer* rbuf, Message* msg,
                   WireError* error = nullptr) noexcept {
  return DecodeMessage(rbuf->data, rbuf->data_size, msg, error);
}

}  // namespace mrsim
