// Decoding a raw LCM buffer. Our handlers subscribe raw rather than typed,
// because lcm-cpp's typed subscriptions drop undecodable messages silently
// and we must count what we drop.
#pragma once

#include <lcm/lcm-cpp.hpp>

namespace mrsim {

// True when `rbuf` decodes as Message (right fingerprint, whole, consistent).
// Never throws: a forged array length makes lcm-gen's decode allocate
// without bound (std::bad_alloc, std::length_error), and a handler called
// from LCM's C code must not let that escape.
template <class Message>
bool DecodeMessage(const lcm::ReceiveBuffer* rbuf, Message* msg) noexcept {
  try {
    return msg->decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0;
  } catch (...) {
    return false;
  }
}

}  // namespace mrsim
