#include "tools/ctl_client.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>

#include "common/wall_time.h"
#include "gait_controller/motion.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/gait_status_timing.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tools/gait_command_request.h"
#include "tools/sim_control_request.h"

namespace mrsim {
namespace {

using Clock = std::chrono::steady_clock;

// s: a simulator sends its status about twice a second.
constexpr double kEverySimulatorHeard = 0.7;

// Keeps the newest decodable message of one type on one channel.
template <class Message>
class Listener {
 public:
  Listener(SignedLcm& lcm, const std::string& channel) : lcm_(lcm) {
    sub_ = lcm_.subscribe(channel, &Listener::On, this);
    sub_->setQueueCapacity(100);
  }
  ~Listener() { lcm_.unsubscribe(sub_); }
  Listener(const Listener&) = delete;
  Listener& operator=(const Listener&) = delete;

  // Handles LCM until a new message satisfies pred or the timeout passes.
  std::optional<Message> Next(const std::function<bool(const Message&)>& pred,
                              double timeout_s) {
    const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (Clock::now() < end) {
      HandleFor(lcm_, 20);
      for (size_t i = 0; i < fresh_.size(); ++i) {
        if (pred(fresh_[i])) {
          Message found = std::move(fresh_[i]);
          // What came after it is for the next call (a STEP's end may
          // arrive with its acknowledgement).
          fresh_.erase(fresh_.begin(), fresh_.begin() + i + 1);
          return found;
        }
      }
      fresh_.clear();
    }
    return std::nullopt;
  }

  // Messages on the channel that did not decode as Message (another
  // version of mrsim, or another program on the same channel).
  int undecodable() const { return undecodable_; }
  // Drops what arrived and Next has not looked at (for a listener only
  // `watch`ed).
  void Forget() { fresh_.clear(); }

  // Called with every message decoded, whether Next wanted it or not.
  std::function<void(const Message&)> watch;

 private:
  // Called from LCM's C code: nothing may escape.
  void On(const lcm::ReceiveBuffer* rbuf, const std::string&) noexcept {
    try {
      Message m;
      if (DecodeMessage(rbuf, &m)) {
        if (watch) watch(m);
        fresh_.push_back(std::move(m));
      } else {
        ++undecodable_;
      }
    } catch (...) {
      ++undecodable_;
    }
  }
  SignedLcm& lcm_;
  lcm::Subscription* sub_ = nullptr;
  std::vector<Message> fresh_;
  int undecodable_ = 0;
};

// Why nothing answered may be that something else did: say so.
std::string UndecodableNote(int count, const std::string& channel) {
  if (count == 0) return "";
  return fmt::format(
      "mrsim-ctl: {} message(s) on {} could not be read (another program on "
      "that channel, or another version of mrsim?)\n",
      count, channel);
}

// with_error: the simulator's last error, which stays in its status after
// the request that caused it (shown by `status` and with a refusal, not
// after a later request that succeeded).
std::string Describe(const sim_status_t& s, bool with_error = true) {
  const char* mode = s.mode == sim_status_t::PAUSED     ? "paused"
                     : s.mode == sim_status_t::STOPPING ? "stopping"
                                                        : "running";
  std::string text = fmt::format(
      "sim time {:.3f} s, {} ({} clock, speed {}), real-time factor {:.2f}, "
      "{} steps; commands applied {}, rejected {}, malformed {}, dropped {}",
      s.sim_time, mode, s.clock, s.speed, s.real_time_factor, s.steps,
      s.commands_applied, s.commands_rejected, s.messages_malformed,
      s.messages_dropped);
  if (!s.waiting_for.empty()) text += "; waiting for " + s.waiting_for;
  if (with_error && !s.last_error.empty()) {
    text += "; last error: " + s.last_error;
  }
  return text;
}

std::string Describe(const gait_status_t& s) {
  std::string text =
      fmt::format("robot {}: motion {} {:.2f}, gait {} ({}){}", s.robot,
                  s.motion, s.strength, s.gait, s.kind,
                  s.running ? "" : ", waiting for the first state");
  // Until the first state the gait above is the old one: what was sent
  // waits, and says so, rather than look ignored.
  if (!s.queued.empty()) {
    text += "; queued: " + s.queued + " (applies with the first state)";
  }
  if (!s.warning.empty()) text += "; warning: " + s.warning;
  return text;
}

// Simulators heard, by instance: the newest status of each.
using Heard = std::map<std::string, sim_status_t>;

// Two simulators on one URL and prefix both take every request: say so,
// listing them.
std::string SeveralSimulatorsNote(const Heard& heard,
                                  const std::string& channel) {
  if (heard.size() < 2) return "";
  std::string text = fmt::format(
      "mrsim-ctl: warning: {} simulators answer on {}; each takes what is "
      "sent there (stop all but one, or give each its own --prefix):\n",
      heard.size(), channel);
  for (const auto& [instance, s] : heard) {
    text += fmt::format("  {}: sim time {:.3f} s, {} clock\n",
                        instance.empty() ? "(unnamed)" : instance, s.sim_time,
                        s.clock);
  }
  return text;
}

int RunSimControl(SignedLcm& lcm, const std::vector<std::string>& words,
                  const CtlOptions& o, std::ostream& out, std::ostream& err) {
  const bool status_only = !words.empty() && words[0] == "status";
  if (status_only && words.size() != 1) {
    throw std::invalid_argument("'status' takes no argument");
  }
  sim_control_t request{};
  if (!status_only) request = ParseSimControl(words);
  const bool file = request.command == sim_control_t::SAVE_CHECKPOINT ||
                    request.command == sim_control_t::LOAD_CHECKPOINT;
  if (file && !status_only) {
    // The simulator opens the path in its own directory, which is seldom
    // the one the user typed the command in (a launch file's, /). Relative
    // paths mean this shell's directory, as for any command; a simulator
    // on another host needs a path that exists there.
    request.path =
        std::filesystem::absolute(request.path).lexically_normal().string();
  }
  Listener<sim_status_t> status(lcm, SimStatusChannel(o.prefix));
  Heard heard;
  status.watch = [&heard](const sim_status_t& s) { heard[s.instance] = s; };
  const auto alive =
      status.Next([](const sim_status_t&) { return true; }, o.timeout);
  if (!alive) {
    err << fmt::format(
        "mrsim-ctl: no answer from a simulator on {} within {:.1f} s (is "
        "mrsim-sim running with the same --lcm-url and --prefix?)\n",
        SimStatusChannel(o.prefix), o.timeout);
    err << UndecodableNote(status.undecodable(), SimStatusChannel(o.prefix));
    return 1;
  }
  if (status_only) {
    // Every simulator sends a status at least twice a second: listening a
    // little longer hears each one.
    status.Next([](const sim_status_t&) { return false; },
                kEverySimulatorHeard);
    if (heard.size() < 2) {
      out << Describe(*alive) << "\n";
      return 0;
    }
    for (const auto& [instance, s] : heard) {
      out << "simulator " << (instance.empty() ? "(unnamed)" : instance) << ": "
          << Describe(s) << "\n";
    }
    err << SeveralSimulatorsNote(heard, SimStatusChannel(o.prefix));
    return 0;
  }
  request.utime = WallMicros();
  request.seq = 1;
  request.sender = o.sender;
  lcm.publish(SimControlChannel(o.prefix), &request);
  const auto ack = status.Next(
      [&](const sim_status_t& s) {
        return s.control_seq == request.seq && s.control_sender == o.sender;
      },
      o.timeout);
  if (!ack) {
    err << fmt::format(
        "mrsim-ctl: {}: sent, but no acknowledgement within "
        "{:.1f} s\n",
        words[0], o.timeout);
    return 1;
  }
  err << SeveralSimulatorsNote(heard, SimStatusChannel(o.prefix));
  if (!ack->control_ok) {
    out << words[0] << ": refused\n" << Describe(*ack) << "\n";
    return 1;
  }
  if (request.command == sim_control_t::STEP) {
    // Acknowledged when taken; done when the periods ran and it paused.
    const int64_t want = ack->state_seq + request.steps;
    const auto stepped = status.Next(
        [&](const sim_status_t& s) {
          return s.mode == sim_status_t::PAUSED && s.state_seq >= want;
        },
        o.timeout);
    if (!stepped) {
      err << fmt::format(
          "mrsim-ctl: step: started; {} periods not done after {:.1f} s "
          "(`mrsim-ctl status` shows how far it got)\n",
          request.steps, o.timeout);
      return 1;
    }
    out << "step: done\n" << Describe(*stepped, false) << "\n";
    return 0;
  }
  if (request.command == sim_control_t::RESUME) {
    // The acknowledgement's real-time factor is over the paused spell
    // (0.00); the next status measures the running one.
    const int64_t acked = ack->seq;
    const auto running = status.Next(
        [&](const sim_status_t& s) {
          return s.instance == ack->instance && s.seq > acked;
        },
        std::min(o.timeout, 2 * kEverySimulatorHeard));
    if (running) {
      out << "resume: done\n" << Describe(*running, false) << "\n";
      return 0;
    }
  }
  out << words[0] << ": done" << (file ? " (" + request.path + ")" : "") << "\n"
      << Describe(*ack, false) << "\n";
  return 0;
}

// The first gait status of `robot`'s steering controller, or nothing. A
// controller that takes gait commands says so with its gait status (at
// least once a second); a robot whose states are heard for
// kGaitStatusWait without one is driven by a controller that takes none
// (a Lua script without on_gait_command, a program of one's own), and
// waiting longer is pointless: `*robot_heard` says so.
std::optional<gait_status_t> WaitForSteering(
    SignedLcm& lcm, Listener<gait_status_t>& status, const std::string& prefix,
    const std::string& robot, double timeout, bool* robot_heard) {
  Listener<robot_state_t> state(lcm, StateChannel(prefix, robot));
  std::optional<Clock::time_point> first_state;
  state.watch = [&](const robot_state_t&) {
    if (!first_state) first_state = Clock::now();
  };
  const auto end = Clock::now() + std::chrono::duration<double>(timeout);
  while (Clock::now() < end) {
    if (auto alive =
            status.Next([](const gait_status_t&) { return true; }, 0.1)) {
      return alive;
    }
    state.Forget();
    if (first_state && Clock::now() - *first_state >
                           std::chrono::duration<double>(kGaitStatusWait)) {
      break;
    }
  }
  *robot_heard = first_state.has_value();
  return std::nullopt;
}

int RunGait(SignedLcm& lcm, const std::vector<std::string>& words,
            const CtlOptions& o, std::ostream& out, std::ostream& err) {
  gait_command_t c = ParseGaitRequest(words);
  const std::string channel = GaitStatusChannel(o.prefix, c.robot);
  Listener<gait_status_t> status(lcm, channel);
  // mrsim-gait says it is there once a second; a command sent before it
  // subscribed would be lost.
  bool robot_heard = false;
  const auto alive =
      WaitForSteering(lcm, status, o.prefix, c.robot, o.timeout, &robot_heard);
  if (!alive && robot_heard) {
    err << fmt::format(
        "mrsim-ctl: nothing steers robot '{}': it runs (its states are on "
        "{}), but its controller takes no gait commands (nothing speaks on "
        "{}). Only a controller that takes steering answers `mrsim-ctl "
        "gait`: mrsim-gait does, and mrsim-lua when the script defines "
        "on_gait_command; a program of one's own when it sends a gait "
        "status\n",
        c.robot, StateChannel(o.prefix, c.robot), channel);
    err << UndecodableNote(status.undecodable(), channel);
    return 1;
  }
  if (!alive) {
    err << fmt::format(
        "mrsim-ctl: no mrsim-gait for robot '{}' answers on {} within {:.1f} "
        "s (robot name misspelled, or mrsim-gait not running with the same "
        "--lcm-url and --prefix?)\n",
        c.robot, channel, o.timeout);
    err << UndecodableNote(status.undecodable(), channel);
    return 1;
  }
  c.utime = WallMicros();
  c.seq = 1;
  c.sender = o.sender;
  lcm.publish(GaitChannel(o.prefix, c.robot), &c);
  const auto ack = status.Next(
      [&](const gait_status_t& s) {
        return s.command_seq == c.seq && s.command_sender == o.sender;
      },
      o.timeout);
  if (!ack) {
    err << fmt::format(
        "mrsim-ctl: gait: sent, but mrsim-gait did not acknowledge it within "
        "{:.1f} s\n",
        o.timeout);
    return 1;
  }
  switch (ack->command_result) {
    case gait_status_t::APPLIED:
      out << "gait: done\n" << Describe(*ack) << "\n";
      return 0;
    case gait_status_t::QUEUED:
      out << "gait: queued (mrsim-gait has no state from the simulator yet; "
             "it applies the command with the first)\n"
          << Describe(*ack) << "\n";
      return 0;
    default:
      // mrsim-lua's status says kind "lua": its script refused.
      err << "mrsim-ctl: gait: refused by "
          << (ack->kind == "lua" ? "the Lua script" : "mrsim-gait") << ": "
          << ack->command_error << "\n"
          << Describe(*ack) << "\n";
      return 1;
  }
}

}  // namespace

std::string CtlHelp() {
  return std::string(
             "Drives a running mrsim-sim, and steers the robots whose "
             "controller takes gait commands (mrsim-gait; mrsim-lua with a "
             "script defining on_gait_command).\n  mrsim-ctl ") +
         SimControlUsage() + "\n  mrsim-ctl status\n  mrsim-ctl " +
         GaitRequestUsage();
}

int RunCtl(SignedLcm& lcm, const std::vector<std::string>& words,
           const CtlOptions& options, std::ostream& out, std::ostream& err) {
  if (!words.empty() && words[0] == "gait") {
    return RunGait(lcm, words, options, out, err);
  }
  return RunSimControl(lcm, words, options, out, err);
}

}  // namespace mrsim
