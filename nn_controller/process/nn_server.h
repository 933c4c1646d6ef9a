// mrsim-nn's LCM adapter: wires one SignedLcm (borrowed from main) and
// steady_clock to an NnNode. Decodes what arrives, hands it to the node
// with the time, publishes what the node returns and prints its lines.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"
#include "nn_controller/process/nn_node.h"

namespace mrsim {

class NnServer {
 public:
  // Subscribes STATE_<robot> and SIM_STATUS. Throws std::runtime_error if
  // LCM cannot subscribe.
  NnServer(SignedLcm& lcm, const NnNodeOptions& options, NnNode node);
  ~NnServer();
  NnServer(const NnServer&) = delete;
  NnServer& operator=(const NnServer&) = delete;

  // Runs until stop_requested(), an error or (with --exit-with-sim) the
  // simulator's end; prints the node's lines to `log`.
  void Run(const std::function<bool()>& stop_requested, std::ostream& log);

  const NnNode& node() const { return node_; }

 private:
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnSimStatus(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

  SignedLcm& lcm_;
  NnNode node_;
  NnOutbox outbox_;
  std::vector<lcm::Subscription*> subscriptions_;
  robot_state_t state_;
  sim_status_t status_;
  std::vector<uint8_t> buffer_;
};

}  // namespace mrsim
