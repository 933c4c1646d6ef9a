// Waits for LCM traffic with poll() on the LCM file descriptor instead of
// lcm_handle_timeout, whose select() aborts on descriptors above 1024.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include "lcmtypes/runtime/signed_lcm.h"

namespace mrsim {

// Handles every message that is ready, waiting up to timeout_ms for the
// first. Returns the number handled (0 on timeout or EINTR); throws
// std::runtime_error if LCM fails.
int HandleFor(lcm::LCM& lcm, int timeout_ms);
int HandleFor(SignedLcm& lcm, int timeout_ms);

}  // namespace mrsim
