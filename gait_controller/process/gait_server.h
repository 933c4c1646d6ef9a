// mrsim-gait's LCM adapter: wires one SignedLcm (borrowed from main),
// steady_clock and optionally the raw keyboard to a GaitNode. Decodes what
// arrives, hands it to the node with the time, publishes what the node
// returns and prints the node's log lines.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "gait_controller/process/gait_node.h"
#include "gait_controller/process/keyboard.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/robot_state_t.hpp"

namespace mrsim {

class GaitServer {
 public:
  // Subscribes STATE_<robot>, GAIT_<robot>, SIM_CONTROL and SIM_STATUS
  // (checkpoints). Throws std::runtime_error if
  // LCM cannot subscribe, std::invalid_argument on bad options.
  GaitServer(SignedLcm& lcm, GaitNodeOptions options,
             std::function<std::vector<Axis>(int)> axes_for, Gait initial);
  ~GaitServer();
  GaitServer(const GaitServer&) = delete;
  GaitServer& operator=(const GaitServer&) = delete;

  // Runs until stop_requested(), q on the keyboard (when `keys` is given)
  // or a node error. Prints the node's lines to `log` ("\r\n" line ends
  // while the terminal is raw).
  void Run(const std::function<bool()>& stop_requested, RawKeyboard* keys,
           std::ostream& log);

  const GaitNode& node() const { return node_; }
  GaitNode& node() { return node_; }

 private:
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnGait(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnSimControl(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnSimStatus(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void Flush();

  SignedLcm& lcm_;
  GaitNode node_;
  GaitOutbox outbox_;
  std::vector<lcm::Subscription*> subscriptions_;
  robot_state_t state_;  // reused: no allocation per state
  gait_command_t gait_;
  sim_control_t control_;
  sim_status_t status_;
  std::vector<uint8_t> buffer_;
};

}  // namespace mrsim
