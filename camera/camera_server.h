// mrsim-camera's LCM adapter: wires one SignedLcm (borrowed from main) and
// steady_clock to a CameraNode. Decodes what arrives, hands it to the node
// with the time, publishes what the node returns and prints its lines.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "camera/camera_node.h"
#include "lcmtypes/runtime/signed_lcm.h"

namespace mrsim {

class CameraServer {
 public:
  // Subscribes to every robot's state, the scene and the simulator's
  // status. Throws std::runtime_error if LCM cannot subscribe.
  CameraServer(SignedLcm& lcm, CameraNode& node);
  ~CameraServer();
  CameraServer(const CameraServer&) = delete;
  CameraServer& operator=(const CameraServer&) = delete;

  // Runs until stop_requested() or (with --exit-with-sim) the simulator's
  // end; prints the node's lines to `log`.
  void Run(const std::function<bool()>& stop_requested, std::ostream& log);

 private:
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnScene(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnSimStatus(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

  SignedLcm& lcm_;
  CameraNode& node_;
  CameraOutbox outbox_;
  std::vector<lcm::Subscription*> subscriptions_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace mrsim
