// The simulator's LCM adapter: owns nothing but the wiring between one
// lcm::LCM (borrowed from main), steady_clock and a SimNode. It decodes what
// arrives, hands it to the node with the time, publishes what the node
// returns and sleeps until the node's next deadline or the next message.
// Outside strict lockstep the sending and receiving run on an LcmIoThread,
// so the physics thread never pays for them; in strict lockstep every state
// waits for its answer anyway, and one thread hop less is the faster loop.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "lcmtypes/runtime/lcm_io_thread.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "sim_core/physics.h"
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
  // Subscribes to <prefix>_COMMAND_* and <prefix>_SIM_CONTROL. Throws
  // std::invalid_argument on bad options, std::runtime_error when LCM
  // cannot subscribe. Warnings go to `log`.
  SimServer(lcm::LCM& lcm, std::unique_ptr<Physics> physics, SimOptions options,
            std::ostream& log);
  ~SimServer();
  SimServer(const SimServer&) = delete;
  SimServer& operator=(const SimServer&) = delete;

  // Runs until QUIT, the duration, or stop_requested() returns true (checked
  // at least every 50 ms). Writes --checkpoint-on-exit before returning.
  // Throws std::runtime_error if LCM fails.
  StopReason Run(const std::function<bool()>& stop_requested);

  const SimNode& node() const { return node_; }
  const Physics& physics() const { return node_.physics(); }
  int steps_per_period() const { return node_.steps_per_period(); }
  double period() const { return node_.period(); }
  const std::string& exit_checkpoint_error() const {
    return node_.exit_checkpoint_error();
  }
  // True when sending and receiving run on a thread of their own.
  bool threaded_io() const;
  // The note main prints when the control period is not exactly 1/rate, or
  // empty; and the start-up line.
  std::string PeriodNote() const;
  std::string StartLine() const;

 private:
  // What a handler received, kept for the node's thread.
  struct Malformed {
    std::string what;
  };
  struct Received {
    std::string channel;
    std::variant<joint_command_t, sim_control_t, Malformed> message;
  };

  void OnCommand(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnControl(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void Receive(Received received);
  // Hands what was received to the node, in arrival order.
  void Deliver();
  // Waits until `due` (at most 50 ms) or until something arrives.
  void Wait(WallTime due);
  void Flush();

  lcm::LCM& lcm_;
  SimNode node_;
  SimOutbox outbox_;
  std::vector<lcm::Subscription*> subscriptions_;
  std::vector<uint8_t> buffer_;
  std::optional<LcmIoThread> io_;  // while Run() runs, when threaded_io()

  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Received> inbox_;    // guarded by mutex_
  std::atomic<bool> mail_{false};  // inbox_ not empty, read without the lock
  std::vector<Received> delivering_;
};

}  // namespace mrsim
