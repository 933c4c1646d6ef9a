// Test-side view of a running mrsim-sim: sends sim_control_t requests and
// keeps the newest status and the states it hears, handling LCM in the test
// thread while it waits.
#pragma once

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim::testing {

class SimClient {
 public:
  explicit SimClient(const std::string& url,
                     const std::string& prefix = kDefaultChannelPrefix)
      : lcm_(url), prefix_(prefix) {
    lcm_.subscribe(SimStatusChannel(prefix), &SimClient::OnStatus, this)
        ->setQueueCapacity(1000);
    lcm_.subscribe(prefix + "_STATE_.*", &SimClient::OnState, this)
        ->setQueueCapacity(1000);
  }

  bool good() { return lcm_.good(); }
  lcm::LCM& lcm() { return lcm_; }

  // Handles traffic until pred() holds or timeout_s passes; returns pred().
  bool WaitFor(const std::function<bool()>& pred, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() +
                     std::chrono::duration<double>(timeout_s);
    while (!pred()) {
      if (std::chrono::steady_clock::now() > end) return false;
      HandleFor(lcm_, 20);
    }
    return true;
  }

  // Sends a request and waits for the status that acknowledges it.
  std::optional<sim_status_t> Control(int8_t command, int32_t steps = 0,
                                      double speed = 0.0,
                                      const std::string& path = "",
                                      double timeout_s = 10.0) {
    sim_control_t msg{};
    msg.seq = ++control_seq_;
    msg.sender = "test";
    msg.command = command;
    msg.steps = steps;
    msg.speed = speed;
    msg.path = path;
    lcm_.publish(SimControlChannel(prefix_), &msg);
    const int64_t seq = msg.seq;
    if (!WaitFor([&] { return status_ && status_->control_seq == seq; },
                 timeout_s)) {
      return std::nullopt;
    }
    return status_;
  }

  // STEP n and wait until the sim is paused again with n more periods done.
  // Fails when no new state came for timeout_s: a loaded machine may make
  // the steps slow, but they must keep coming.
  //
  // Steps at most kStepBurst periods per request: a lockstep burst of 60
  // states and their 60 answers outgrows the test's socket buffer when a
  // loaded machine leaves the test unscheduled, and the state that ends a
  // STEP is published once (seen: a test waiting 20 s for the state the
  // kernel dropped).
  bool StepAndWait(int periods, double timeout_s = 20.0) {
    constexpr int kStepBurst = 10;
    for (int done = 0; done < periods; done += kStepBurst) {
      if (!StepBurst(std::min(kStepBurst, periods - done), timeout_s)) {
        return false;
      }
    }
    return true;
  }

  const std::optional<sim_status_t>& status() const { return status_; }
  // What the newest status says, for a failure message.
  std::string Describe() const {
    if (!status_) return "no status heard";
    const sim_status_t& s = *status_;
    return "status: mode " + std::to_string(s.mode) + ", state_seq " +
           std::to_string(s.state_seq) + ", states published " +
           std::to_string(s.states_published) + ", commands applied " +
           std::to_string(s.commands_applied) + ", rejected " +
           std::to_string(s.commands_rejected) + " (seq " +
           std::to_string(s.rejected_seq) + ", sender " +
           std::to_string(s.rejected_sender) + "), dropped " +
           std::to_string(s.messages_dropped) + ", waiting for '" +
           s.waiting_for + "', last state heard " +
           std::to_string(last_state_seq_) + ", states heard " +
           std::to_string(states_received_);
  }
  // Newest state of each robot, by robot name.
  const std::map<std::string, robot_state_t>& states() const { return states_; }
  int64_t last_state_seq() const { return last_state_seq_; }
  int states_received() const { return states_received_; }

 private:
  bool StepBurst(int periods, double timeout_s) {
    if (!status_) return false;
    const int64_t want = status_->state_seq + periods;
    if (!Control(sim_control_t::STEP, periods)) return false;
    const auto done = [&] {
      return status_->state_seq >= want &&
             status_->mode == sim_status_t::PAUSED && last_state_seq_ >= want;
    };
    while (!done()) {
      const int64_t seen = last_state_seq_;
      if (!WaitFor([&] { return done() || last_state_seq_ > seen; },
                   timeout_s)) {
        return false;
      }
    }
    return true;
  }

  void OnStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    sim_status_t s;
    if (DecodeMessage(rbuf, &s)) {
      status_ = s;
    }
  }
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    robot_state_t s;
    if (DecodeMessage(rbuf, &s)) {
      if (s.seq > last_state_seq_) last_state_seq_ = s.seq;
      ++states_received_;
      states_[s.robot] = s;
    }
  }

  lcm::LCM lcm_;
  std::string prefix_;
  int64_t control_seq_ = 0;
  std::optional<sim_status_t> status_;
  std::map<std::string, robot_state_t> states_;
  int64_t last_state_seq_ = -1;
  int states_received_ = 0;
};

// The 11-module snake the tests drive: scenarios/snake11.xml when present,
// otherwise the same chain generated with MakeChain into `dir`.
inline std::string TestScenarioPath(const std::string& dir) {
  const std::string stock = SourcePath("scenarios/snake11.xml");
  if (std::filesystem::exists(stock)) return stock;
  Scenario scenario;
  ChainOptions options;
  options.name = "snake";
  options.modules = 11;
  scenario.robots.push_back(MakeChain(options));
  const std::string path = dir + "/snake11.xml";
  WriteScenarioFile(scenario, path);
  return path;
}

inline std::string SimBinary() {
  return BinaryPath("sim_core/sim_process/mrsim-sim");
}
inline std::string ControllerBinary() {
  return BinaryPath("tests/sim_process/mrsim-test-controller");
}

}  // namespace mrsim::testing
