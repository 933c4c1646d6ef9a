// mrsim-lua's LCM adapter: wires one SignedLcm (borrowed from main) and
// steady_clock to a LuaNode. Decodes what arrives, hands it to the node
// with the time, publishes what the node returns and prints its lines.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/signed_lcm.h"
#include "lua_controller/process/lua_node.h"

namespace mrsim {

class LuaServer {
 public:
  // Subscribes STATE_<robot> and SIM_STATUS, GAIT_<robot> when the
  // script takes steering (on_gait_command), and CAMERA_<robot> and
  // COMMAND_<robot> (the camera process's answers) unless the robot has
  // no camera (options.cameras == 0). Throws std::runtime_error if
  // LCM cannot subscribe.
  LuaServer(SignedLcm& lcm, LuaNodeOptions options, LuaNode node);
  ~LuaServer();
  LuaServer(const LuaServer&) = delete;
  LuaServer& operator=(const LuaServer&) = delete;

  // Runs until stop_requested(), a script error or (with --exit-with-sim)
  // the simulator's end; prints the node's lines to `log`.
  void Run(const std::function<bool()>& stop_requested, std::ostream& log);

  const LuaNode& node() const { return node_; }

 private:
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnSimStatus(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnGaitCommand(const lcm::ReceiveBuffer* rbuf,
                     const std::string& channel);
  void OnCameraImage(const lcm::ReceiveBuffer* rbuf,
                     const std::string& channel);
  void OnCommand(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

  SignedLcm& lcm_;
  LuaNode node_;
  LuaOutbox outbox_;
  std::vector<lcm::Subscription*> subscriptions_;
  robot_state_t state_;
  sim_status_t status_;
  gait_command_t command_;
  camera_image_t image_;
  joint_command_t answer_;
  std::vector<uint8_t> buffer_;
};

}  // namespace mrsim
