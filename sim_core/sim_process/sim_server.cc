#include "sim_core/sim_process/sim_server.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/wall_time.h"
#include "lcmtypes/runtime/channel_pattern.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {
namespace {

// "host:pid": unique among the simulators one LCM URL reaches.
SimOptions WithInstance(SimOptions options) {
  if (!options.instance.empty()) return options;
  char host[256] = {};
  if (gethostname(host, sizeof(host) - 1) != 0) host[0] = '\0';
  options.instance = std::string(host[0] ? host : "localhost") + ":" +
                     std::to_string(getpid());
  return options;
}

}  // namespace

SimServer::SimServer(SignedLcm& lcm, std::unique_ptr<Physics> physics,
                     SimOptions options, std::ostream& log)
    : lcm_(lcm),
      node_(std::move(physics), WithInstance(std::move(options)), log,
            WallClock::now()) {
  const std::string& prefix = node_.options().prefix;
  lcm::Subscription* commands =
      lcm_.subscribe(LiteralChannelPattern(CommandChannel(prefix, "")) + ".*",
                     &SimServer::OnCommand, this);
  lcm::Subscription* control =
      lcm_.subscribe(SimControlChannel(prefix), &SimServer::OnControl, this);
  lcm::Subscription* status =
      lcm_.subscribe(SimStatusChannel(prefix), &SimServer::OnStatus, this);
  if (commands == nullptr || control == nullptr || status == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  commands->setQueueCapacity(kCommandQueueCapacity);
  control->setQueueCapacity(kControlQueueCapacity);
  subscriptions_ = {commands, control, status};
  const SimOptions& o = node_.options();
  if (o.clock == ClockMode::kLockstep && (o.actuation_delay > 0 || o.spin)) {
    publisher_ = std::make_unique<PublishThread>(
        lcm_,
        o.spin ? PublishThread::Wait::kSpin : PublishThread::Wait::kSleep);
  }
}

SimServer::~SimServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

StopReason SimServer::Run(const std::function<bool()>& stop_requested) {
  node_.Start(WallClock::now(), &outbox_);
  Flush();
  while (!node_.stopped()) {
    if (stop_requested()) {
      node_.Stop(StopReason::kSignal, WallClock::now(), &outbox_);
      Flush();
      break;
    }
    const WallTime due = node_.Tick(WallClock::now(), &outbox_);
    Flush();
    if (node_.stopped()) break;
    const double wait = SecondsBetween(WallClock::now(), due);
    const int wait_ms =
        wait <= 0 ? 0 : std::min(50, static_cast<int>(std::ceil(wait * 1e3)));
    HandleFor(lcm_, wait_ms);
  }
  // The last status (stopped) is out before main goes on.
  if (publisher_) publisher_->Drain();
  return *node_.stopped();
}

// On udpm the sender's thread pays for every local subscriber's delivery
// (a fifth of a period for this snake): in lockstep that goes to the
// publisher's thread, on another core. A sleeping publisher thread costs
// the physics thread a wake-up instead, which only pays with a pipelined
// lockstep (strict lockstep waits for the answer anyway, and the hand-over
// would add to its round trip); a spinning one costs it nothing.
void SimServer::Flush() {
  if (publisher_) {
    PublishAll(*publisher_, &outbox_, &buffer_);
  } else {
    PublishAll(lcm_, &outbox_, &buffer_);
  }
}

// LCM calls the handlers from C: nothing may escape them.
void SimServer::OnCommand(const lcm::ReceiveBuffer* rbuf,
                          const std::string& channel) {
  try {
    // lcm-gen's decode does not empty an array whose count is 0: an
    // answer without targets must not carry the previous command's.
    command_.target.clear();
    if (!DecodeMessage(rbuf, &command_)) {
      node_.OnMalformed("");
      return;
    }
    node_.OnCommand(command_, channel, WallClock::now());
  } catch (const std::exception& e) {
    // e.g. an absurd array length in a forged message
    node_.OnMalformed("command on " + channel + ": " + e.what());
  } catch (...) {
    node_.OnMalformed("");
  }
}

void SimServer::OnControl(const lcm::ReceiveBuffer* rbuf,
                          const std::string& channel) {
  try {
    if (!DecodeMessage(rbuf, &control_)) {
      node_.OnMalformed("");
      return;
    }
    node_.OnControl(control_, WallClock::now(), &outbox_);
    Flush();
  } catch (const std::exception& e) {
    node_.OnMalformed("control on " + channel + ": " + e.what());
  } catch (...) {
    node_.OnMalformed("");
  }
}

void SimServer::OnStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  try {
    // Not counted as malformed when unreadable: a simulator of another
    // version may publish there, and our own statuses come back too.
    if (DecodeMessage(rbuf, &status_)) node_.OnSimStatus(status_);
  } catch (...) {
  }
}

std::string SimServer::PeriodNote() const {
  const double wanted = 1.0 / node_.options().rate;
  if (std::abs(period() - wanted) <= 1e-9) return "";
  std::ostringstream out;
  out << "mrsim-sim: note: control period " << period() << " s ("
      << steps_per_period() << " physics steps of " << physics().timestep()
      << " s) instead of 1/" << node_.options().rate << " s";
  return out.str();
}

std::string SimServer::StartLine() const {
  const SimOptions& o = node_.options();
  std::ostringstream out;
  out << "mrsim-sim: " << physics().robot_count() << " robot(s), clock "
      << ToString(o.clock);
  if (o.actuation_delay > 0) {
    out << " (actuation delay " << o.actuation_delay << ")";
  }
  out << ", " << 1.0 / period() << " Hz control, " << steps_per_period()
      << " steps of " << physics().timestep() << " s per period, prefix "
      << o.prefix << (o.paused ? ", paused" : "");
  return out.str();
}

}  // namespace mrsim
