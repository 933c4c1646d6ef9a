#include "sim_core/sim_process/sim_server.h"

#include <glib.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/wall_time.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"

namespace mrsim {
namespace {

std::string EscapeRegex(const std::string& text) {
  std::unique_ptr<gchar, decltype(&g_free)> escaped(
      g_regex_escape_string(text.c_str(), static_cast<gint>(text.size())),
      &g_free);
  return escaped.get();
}

// How long the physics thread spins for a lockstep answer before it sleeps.
constexpr double kAnswerSpin = 150e-6;

}  // namespace

SimServer::SimServer(lcm::LCM& lcm, std::unique_ptr<Physics> physics,
                     SimOptions options, std::ostream& log)
    : lcm_(lcm),
      node_(std::move(physics), std::move(options), log, WallClock::now()) {
  const std::string& prefix = node_.options().prefix;
  lcm::Subscription* commands =
      lcm_.subscribe(EscapeRegex(CommandChannel(prefix, "")) + ".*",
                     &SimServer::OnCommand, this);
  lcm::Subscription* control =
      lcm_.subscribe(SimControlChannel(prefix), &SimServer::OnControl, this);
  if (commands == nullptr || control == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  commands->setQueueCapacity(kCommandQueueCapacity);
  control->setQueueCapacity(kControlQueueCapacity);
  subscriptions_ = {commands, control};
}

SimServer::~SimServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

bool SimServer::threaded_io() const {
  const SimOptions& o = node_.options();
  return o.clock != ClockMode::kLockstep || o.actuation_delay > 0;
}

StopReason SimServer::Run(const std::function<bool()>& stop_requested) {
  if (threaded_io()) io_.emplace(lcm_);
  node_.Start(WallClock::now(), &outbox_);
  Flush();
  while (!node_.stopped()) {
    if (stop_requested()) {
      node_.Stop(StopReason::kSignal, WallClock::now(), &outbox_);
      Flush();
      break;
    }
    Deliver();
    const WallTime due = node_.Tick(WallClock::now(), &outbox_);
    Flush();
    if (node_.stopped()) break;
    Wait(due);
  }
  if (io_) {
    io_->Stop();  // sends the final status; rethrows an LCM failure
    io_.reset();
  }
  return *node_.stopped();
}

void SimServer::Flush() {
  if (io_) {
    io_->PublishAll(&outbox_);
  } else {
    PublishAll(lcm_, &outbox_, &buffer_);
  }
}

void SimServer::Wait(WallTime due) {
  const WallTime now = WallClock::now();
  const double wait = SecondsBetween(now, due);
  const int wait_ms =
      wait <= 0 ? 0 : std::min(50, static_cast<int>(std::ceil(wait * 1e3)));
  if (!io_) {
    HandleFor(lcm_, wait_ms);  // the handlers fill the inbox
    return;
  }
  if (node_.AwaitingAnswers()) {
    // An answer is usually due within a round trip; a sleep and its
    // wake-up would cost as much again.
    const WallTime spin_end = AfterSeconds(now, std::min(wait, kAnswerSpin));
    while (!mail_.load(std::memory_order_acquire) &&
           WallClock::now() < spin_end) {
    }
  }
  std::unique_lock<std::mutex> lock(mutex_);
  arrived_.wait_until(lock, now + std::chrono::milliseconds(wait_ms),
                      [this] { return !inbox_.empty(); });
}

void SimServer::Receive(Received received) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    inbox_.push_back(std::move(received));
    mail_.store(true, std::memory_order_release);
  }
  arrived_.notify_one();
}

void SimServer::Deliver() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    delivering_.swap(inbox_);
    mail_.store(false, std::memory_order_release);
  }
  for (const Received& r : delivering_) {
    const WallTime now = WallClock::now();
    if (const auto* cmd = std::get_if<joint_command_t>(&r.message)) {
      node_.OnCommand(*cmd, r.channel, now);
    } else if (const auto* ctl = std::get_if<sim_control_t>(&r.message)) {
      node_.OnControl(*ctl, now, &outbox_);
      Flush();
    } else {
      node_.OnMalformed(std::get<Malformed>(r.message).what);
    }
  }
  delivering_.clear();
}

// LCM calls the handlers from C (on the I/O thread when there is one):
// nothing may escape them, and they touch nothing but the inbox.
void SimServer::OnCommand(const lcm::ReceiveBuffer* rbuf,
                          const std::string& channel) {
  try {
    joint_command_t cmd;
    if (!DecodeMessage(rbuf, &cmd)) {
      Receive({channel, Malformed{""}});
      return;
    }
    Receive({channel, std::move(cmd)});
  } catch (const std::exception& e) {
    // e.g. an absurd array length in a forged message
    Receive({channel, Malformed{"command on " + channel + ": " + e.what()}});
  } catch (...) {
    Receive({channel, Malformed{""}});
  }
}

void SimServer::OnControl(const lcm::ReceiveBuffer* rbuf,
                          const std::string& channel) {
  try {
    sim_control_t control;
    if (!DecodeMessage(rbuf, &control)) {
      Receive({channel, Malformed{""}});
      return;
    }
    Receive({channel, std::move(control)});
  } catch (const std::exception& e) {
    Receive({channel, Malformed{"control on " + channel + ": " + e.what()}});
  } catch (...) {
    Receive({channel, Malformed{""}});
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
