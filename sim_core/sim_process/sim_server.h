// The simulator's LCM adapter: owns nothing but the wiring between one
// SignedLcm (borrowed from main), steady_clock and a SimNode. It decodes what
// arrives, hands it to the node with the time, publishes what the node
// returns and sleeps on the LCM socket until the node's next deadline.
#pragma once

#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/publish_thread.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "sim_core/physics/physics.h"
#include "sim_core/sim_process/sim_node.h"
#include "sim_core/sim_process/sim_options.h"
#include "sim_core/sim_process/sim_outbox.h"

namespace mrsim {

// Subscription queue capacities (messages). LCM 1.3.1 keeps 30 per
// subscription and drops the newest beyond; see docs/sim.md for why these.
inline constexpr int kCommandQueueCapacity = 2000;
inline constexpr int kControlQueueCapacity = 200;

class SimServer {
 public:
  // Subscribes to <prefix>_COMMAND_* and <prefix>_SIM_CONTROL, and to
  // <prefix>_SIM_STATUS to hear another simulator there. Throws
  // std::invalid_argument on bad options, std::runtime_error when LCM
  // cannot subscribe. Warnings go to `log`.
  SimServer(SignedLcm& lcm, std::unique_ptr<Physics> physics,
            SimOptions options, std::ostream& log);
  ~SimServer();
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  // Runs until QUIT, the duration, or stop_requested() returns true (checked
  // at least every 50 ms). Writes --checkpoint-on-exit before returning.
  StopReason Run(const std::function<bool()>& stop_requested);

  const SimNode& node() const { return node_; }
  const Physics& physics() const { return node_.physics(); }
  int steps_per_period() const { return node_.steps_per_period(); }
  double period() const { return node_.period(); }
  const std::string& exit_checkpoint_error() const {
    return node_.exit_checkpoint_error();
  }
  // The note main prints when the control period is not exactly 1/rate, or
  // empty; and the start-up line.
  std::string PeriodNote() const;
  std::string StartLine() const;

 private:
  void OnCommand(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnControl(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnStatus(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void Flush();

  SignedLcm& lcm_;
  SimNode node_;
  SimOutbox outbox_;
  std::vector<lcm::Subscription*> subscriptions_;
  // Reused for every message: no allocation per period.
  joint_command_t command_;
  sim_control_t control_;
  sim_status_t status_;
  std::vector<uint8_t> buffer_;
  // Pipelined lockstep sends from a thread of its own (see Flush).
  std::unique_ptr<PublishThread> publisher_;
};

}  // namespace mrsim
