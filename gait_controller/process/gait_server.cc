#include "gait_controller/process/gait_server.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/printable.h"
#include "gait_controller/process/key_command.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {
namespace {

constexpr int kStateQueueCapacity = 100;
constexpr int kGaitQueueCapacity = 100;

}  // namespace

GaitServer::GaitServer(SignedLcm& lcm, GaitNodeOptions options,
                       std::function<std::vector<Axis>(int)> axes_for,
                       Gait initial)
    : lcm_(lcm),
      node_(options, std::move(axes_for), std::move(initial),
            WallClock::now()) {
  lcm::Subscription* state = lcm_.subscribe(
      StateChannel(options.prefix, options.robot), &GaitServer::OnState, this);
  lcm::Subscription* gait = lcm_.subscribe(
      GaitChannel(options.prefix, options.robot), &GaitServer::OnGait, this);
  if (state == nullptr || gait == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  lcm::Subscription* control = lcm_.subscribe(SimControlChannel(options.prefix),
                                              &GaitServer::OnSimControl, this);
  lcm::Subscription* status = lcm_.subscribe(SimStatusChannel(options.prefix),
                                             &GaitServer::OnSimStatus, this);
  if (control == nullptr || status == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  state->setQueueCapacity(kStateQueueCapacity);
  gait->setQueueCapacity(kGaitQueueCapacity);
  control->setQueueCapacity(kGaitQueueCapacity);
  status->setQueueCapacity(kGaitQueueCapacity);
  subscriptions_ = {state, gait, control, status};
}

GaitServer::~GaitServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

void GaitServer::Flush() { PublishAll(lcm_, &outbox_, &buffer_); }

// LCM calls the handlers from C: nothing may escape them.
void GaitServer::OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    if (!DecodeMessage(rbuf, &state_)) {
      node_.OnMalformedState();
      return;
    }
    node_.OnState(state_, WallClock::now(), &outbox_);
    Flush();
  } catch (...) {
    node_.OnMalformedState();
  }
}

void GaitServer::OnGait(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    if (!DecodeMessage(rbuf, &gait_)) {
      node_.OnMalformedGait(WallClock::now(), &outbox_);
    } else {
      node_.OnGaitCommand(gait_, WallClock::now(), &outbox_);
    }
    Flush();
  } catch (...) {
    // Counted as a rejected command, and said so in the status the sender
    // waits for.
    try {
      node_.OnMalformedGait(WallClock::now(), &outbox_);
      Flush();
    } catch (...) {
    }
  }
}

// Foreign or broken traffic on the simulator's channels is not ours to
// count: the simulator counts it.
void GaitServer::OnSimControl(const lcm::ReceiveBuffer* rbuf,
                              const std::string&) {
  try {
    if (DecodeMessage(rbuf, &control_)) node_.OnSimControl(control_);
  } catch (...) {
  }
}

void GaitServer::OnSimStatus(const lcm::ReceiveBuffer* rbuf,
                             const std::string&) {
  try {
    if (DecodeMessage(rbuf, &status_)) {
      node_.OnSimStatus(status_, WallClock::now(), &outbox_);
      Flush();
    }
  } catch (...) {
  }
}

void GaitServer::Run(const std::function<bool()>& stop_requested,
                     RawKeyboard* keys, std::ostream& log) {
  // RawKeyboard leaves output processing on: the terminal still turns
  // '\n' into "\r\n".
  const char* eol = "\n";
  if (keys) log << "mrsim-gait: " << KeyHelp() << eol;
  node_.Start(WallClock::now(), &outbox_);
  Flush();
  bool quit = false;
  while (!quit && !stop_requested() && node_.error().empty() && !node_.done()) {
    const WallTime due = node_.Tick(WallClock::now(), &outbox_);
    Flush();
    const double wait = SecondsBetween(WallClock::now(), due);
    const int limit_ms = keys ? 20 : 100;
    HandleFor(lcm_,
              std::clamp(static_cast<int>(std::ceil(wait * 1e3)), 0, limit_ms));
    while (keys) {
      const auto key = keys->Poll();
      if (!key) break;
      bool help = false;
      if (auto c = KeyCommand(*key, node_.controller(), &quit, &help)) {
        node_.Apply(*c, "keyboard", WallClock::now(), &outbox_);
        Flush();
      }
      if (help) log << "mrsim-gait: " << KeyHelp() << eol;
    }
    for (const std::string& line : node_.TakeLog()) {
      log << "mrsim-gait: " << Printable(line) << eol;
    }
    log.flush();
  }
}

}  // namespace mrsim
