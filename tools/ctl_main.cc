// mrsim-ctl: drive a running simulation from the shell.
//   mrsim-ctl pause | resume | step N | reset | save PATH | load PATH |
//             speed S | quit      (waits for the simulator's acknowledgement)
//   mrsim-ctl status              (prints the next heartbeat)
//   mrsim-ctl gait ROBOT [gait NAME] [motion M] [strength S] [direction F T]
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "common/wall_time.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tools/sim_control_request.h"

namespace {

using Clock = std::chrono::steady_clock;

// Keeps the newest status; counts what does not decode.
class StatusListener {
 public:
  void OnStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    mrsim::sim_status_t s;
    if (!mrsim::DecodeMessage(rbuf, &s)) {
      ++malformed_;
      return;
    }
    latest_ = s;
    ++received_;
  }
  const mrsim::sim_status_t& latest() const { return latest_; }
  int received() const { return received_; }

 private:
  mrsim::sim_status_t latest_{};
  int received_ = 0;
  int malformed_ = 0;
};

std::string Describe(const mrsim::sim_status_t& s) {
  const char* mode = s.mode == mrsim::sim_status_t::PAUSED     ? "paused"
                     : s.mode == mrsim::sim_status_t::STOPPING ? "stopping"
                                                               : "running";
  std::string text = fmt::format(
      "sim time {:.3f} s, {} ({} clock, speed {}), real-time factor {:.2f}, "
      "{} steps; commands applied {}, rejected {}, malformed {}, dropped {}",
      s.sim_time, mode, s.clock, s.speed, s.real_time_factor, s.steps,
      s.commands_applied, s.commands_rejected, s.messages_malformed,
      s.messages_dropped);
  if (!s.waiting_for.empty()) text += "; waiting for " + s.waiting_for;
  if (!s.last_error.empty()) text += "; last error: " + s.last_error;
  return text;
}

double Number(const std::vector<std::string>& words, size_t i,
              const std::string& what) {
  if (i >= words.size()) throw std::invalid_argument(what + ": missing value");
  try {
    size_t used = 0;
    const double v = std::stod(words[i], &used);
    if (used != words[i].size()) throw std::invalid_argument("");
    return v;
  } catch (const std::exception&) {
    throw std::invalid_argument(what + ": expected a number, got '" + words[i] +
                                "'");
  }
}

mrsim::gait_command_t ParseGait(const std::vector<std::string>& words) {
  if (words.size() < 3) {
    throw std::invalid_argument(
        "gait ROBOT [gait NAME] [motion M] [strength S] [direction F T]");
  }
  mrsim::gait_command_t c{};
  c.robot = words[1];
  c.strength = 1.0;
  for (size_t i = 2; i < words.size(); ++i) {
    const std::string& key = words[i];
    if (key == "gait" && i + 1 < words.size()) {
      c.gait = words[++i];
    } else if (key == "motion" && i + 1 < words.size()) {
      c.motion = words[++i];
    } else if (key == "strength") {
      c.strength = Number(words, ++i, "strength");
    } else if (key == "direction") {
      c.has_direction = true;
      c.forward = Number(words, ++i, "direction forward");
      c.turn = Number(words, ++i, "direction turn");
    } else {
      throw std::invalid_argument("gait: unexpected '" + key +
                                  "'; expected gait, motion, strength or "
                                  "direction");
    }
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    CLI::App app{
        "Drives a running mrsim-sim and mrsim-gait from the shell.\n"
        "  mrsim-ctl pause | resume | step N | reset | save PATH | load PATH "
        "| speed S | quit\n"
        "  mrsim-ctl status\n"
        "  mrsim-ctl gait ROBOT [gait NAME] [motion M] [strength S] "
        "[direction F T]"};
    std::string lcm_url;
    std::string prefix = mrsim::kDefaultChannelPrefix;
    double timeout = 5.0;
    std::vector<std::string> words;
    app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
    app.add_option("--prefix", prefix, "Channel prefix")->capture_default_str();
    app.add_option("--timeout", timeout,
                   "Seconds to wait for the simulator's answer")
        ->capture_default_str();
    app.add_option("command", words, "The command and its arguments")
        ->required();
    app.positionals_at_end();
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e) == 0 ? 0 : 2;
    }

    lcm::LCM lcm(lcm_url);
    if (!lcm.good()) {
      std::fprintf(stderr, "mrsim-ctl: cannot open LCM '%s'\n",
                   lcm_url.c_str());
      return 1;
    }

    if (words[0] == "gait") {
      mrsim::gait_command_t c = ParseGait(words);
      c.utime = mrsim::WallMicros();
      c.seq = c.utime;
      c.sender = "mrsim-ctl";
      lcm.publish(mrsim::GaitChannel(prefix, c.robot), &c);
      std::printf("sent to %s (mrsim-gait prints a line if it rejects it)\n",
                  mrsim::GaitChannel(prefix, c.robot).c_str());
      return 0;
    }

    const bool status_only = words.size() == 1 && words[0] == "status";
    mrsim::sim_control_t request{};
    if (!status_only) request = mrsim::ParseSimControl(words);
    StatusListener listener;
    lcm.subscribe(mrsim::SimStatusChannel(prefix), &StatusListener::OnStatus,
                  &listener);
    // Send only once a heartbeat shows the simulator is there: a request
    // published before it subscribed would be lost, and resending could
    // apply a STEP twice.
    bool sent = false;
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout);
    while (Clock::now() < deadline) {
      const int before = listener.received();
      mrsim::HandleFor(lcm, 50);
      if (listener.received() == before) continue;
      const mrsim::sim_status_t& s = listener.latest();
      if (status_only) {
        std::printf("%s\n", Describe(s).c_str());
        return 0;
      }
      if (!sent) {
        request.utime = mrsim::WallMicros();
        request.seq = request.utime;  // unique enough to match the answer
        request.sender = "mrsim-ctl";
        lcm.publish(mrsim::SimControlChannel(prefix), &request);
        sent = true;
        continue;
      }
      if (s.control_seq == request.seq) {
        std::printf("%s: %s\n%s\n", words[0].c_str(),
                    s.control_ok ? "done" : "refused", Describe(s).c_str());
        return s.control_ok ? 0 : 1;
      }
    }
    std::fprintf(stderr,
                 "mrsim-ctl: no answer from a simulator on %s within %.1f s "
                 "(is mrsim-sim running with the same --lcm-url and "
                 "--prefix?)\n",
                 mrsim::SimStatusChannel(prefix).c_str(), timeout);
    return 1;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrsim-ctl: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-ctl: %s\n", e.what());
    return 1;
  }
}
