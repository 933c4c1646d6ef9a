#include "studio/live/opt_progress_link.h"

#include <stdexcept>
#include <utility>

#include "common/lcm_url.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {

OptProgressLink::OptProgressLink(const std::string& url,
                                 const std::string& channel, Handler handler)
    : lcm_(url), handler_(std::move(handler)) {
  if (!lcm_.good()) {
    throw std::runtime_error(CannotOpenLcm(url) +
                             " (for the optimisation's progress)");
  }
  subscription_ = lcm_.subscribe(channel, &OptProgressLink::OnRaw, this);
}

OptProgressLink::~OptProgressLink() {
  if (subscription_ != nullptr) lcm_.unsubscribe(subscription_);
}

void OptProgressLink::OnRaw(const lcm::ReceiveBuffer* rbuf,
                            const std::string&) {
  opt_progress_t m;
  if (!DecodeMessage(rbuf->data, rbuf->data_size, &m)) {
    ++malformed_;
    return;
  }
  handler_(m);
}

int OptProgressLink::Poll() { return HandleFor(lcm_, 0); }

}  // namespace mrsim
