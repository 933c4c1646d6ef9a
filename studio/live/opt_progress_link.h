// The optimisation session's connection for mrsim-opt's progress: hears
// opt_progress_t on one channel of one LCM URL and hands each decoded
// message on; counts what does not decode. Polled from the frame loop.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "mrsim/opt_progress_t.hpp"

namespace mrsim {

class OptProgressLink {
 public:
  using Handler = std::function<void(const opt_progress_t&)>;
  // Throws std::runtime_error naming the URL when LCM cannot open it.
  OptProgressLink(const std::string& url, const std::string& channel,
                  Handler handler);
  ~OptProgressLink();
  OptProgressLink(const OptProgressLink&) = delete;
  OptProgressLink& operator=(const OptProgressLink&) = delete;

  // Hands on what arrived (no waiting); returns how many messages.
  int Poll();
  int64_t malformed() const { return malformed_; }

 private:
  void OnRaw(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

  lcm::LCM lcm_;
  Handler handler_;
  lcm::Subscription* subscription_ = nullptr;
  int64_t malformed_ = 0;
};

}  // namespace mrsim
