#include "nn_controller/process/nn_server.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/printable.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {
namespace {

void WriteLog(const std::vector<std::string>& lines, std::ostream& log) {
  for (const std::string& line : lines) {
    log << "mrsim-nn: " << Printable(line) << "\n";
  }
}

}  // namespace

NnServer::NnServer(SignedLcm& lcm, const NnNodeOptions& options, NnNode node)
    : lcm_(lcm), node_(std::move(node)) {
  lcm::Subscription* state = lcm_.subscribe(
      StateChannel(options.prefix, options.robot), &NnServer::OnState, this);
  lcm::Subscription* status = lcm_.subscribe(SimStatusChannel(options.prefix),
                                             &NnServer::OnSimStatus, this);
  if (state == nullptr || status == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  state->setQueueCapacity(100);
  status->setQueueCapacity(100);
  subscriptions_ = {state, status};
}

NnServer::~NnServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

// LCM calls the handlers from C: nothing may escape them.
void NnServer::OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    if (!DecodeMessage(rbuf, &state_)) {
      node_.OnMalformedState();
      return;
    }
    node_.OnState(state_, WallClock::now(), &outbox_);
    PublishAll(lcm_, &outbox_, &buffer_);
  } catch (...) {
    node_.OnMalformedState();
  }
}

// Foreign traffic on the simulator's channel is the simulator's to count.
void NnServer::OnSimStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    if (DecodeMessage(rbuf, &status_)) {
      node_.OnSimStatus(status_, WallClock::now());
    }
  } catch (...) {
  }
}

void NnServer::Run(const std::function<bool()>& stop_requested,
                   std::ostream& log) {
  while (!stop_requested() && node_.error().empty() && !node_.done()) {
    const WallTime due = node_.Tick(WallClock::now());
    const double wait = SecondsBetween(WallClock::now(), due);
    HandleFor(lcm_,
              std::clamp(static_cast<int>(std::ceil(wait * 1e3)), 0, 100));
    WriteLog(node_.TakeLog(), log);
    log.flush();
  }
  WriteLog(node_.TakeLog(), log);
}

}  // namespace mrsim
