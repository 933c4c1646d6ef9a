// mrsim-nn's logic as a plain state machine: answers each state of one
// robot with the targets of a neural-network controller (MlpNetwork; the
// state's sim time is its clock, so a lockstep run is the same every time
// and equals the optimiser's episode, MlpEpisodeController). Decoded messages
// and the wall time in, joint commands out; NnServer is the LCM adapter.
// The network takes no steering, so the node sends no gait status (the
// studio and mrsim-ctl then see the robot as not steerable, which it is
// not). A robot of another joint count than the network's stops the node
// (error()): every state would fail the same way.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/outbox.h"
#include "lcmtypes/runtime/simulator_watch.h"
#include "lcmtypes/runtime/state_pacer.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "nn_controller/mlp_network.h"

namespace mrsim {

using NnOutbox = Outbox<joint_command_t>;

struct NnNodeOptions {
  std::string robot;
  std::string prefix = kDefaultChannelPrefix;
  std::string sender;  // joint_command_t.sender
  // Hz of sim time: states closer together than 1/rate are not answered
  // (0: every state); a lockstep simulator makes it answer every state.
  double rate = 100.0;
  bool exit_with_sim = false;
};

struct NnNodeCounters {
  int64_t states_answered = 0;
  int64_t states_repeated = 0;
  int64_t states_skipped = 0;
  int64_t states_foreign = 0;
  int64_t messages_malformed = 0;
};

// The state's inputs for the network, as ObservationOf reads them from the
// physics (nn_observation.h).
void ObservationOfMessage(const robot_state_t& state, NnObservation* out);

class NnNode {
 public:
  static constexpr double kMaxSimTime = 1e9;  // s; later states are forged

  // Throws std::invalid_argument on a bad rate.
  NnNode(NnNodeOptions options, MlpNetwork network, WallTime now);

  void OnState(const robot_state_t& state, WallTime now, NnOutbox* out);
  void OnMalformedState() { ++counters_.messages_malformed; }
  void OnSimStatus(const sim_status_t& status, WallTime now);
  // Warnings and, with exit_with_sim, a silent simulator; returns when it
  // wants to be called again.
  WallTime Tick(WallTime now);

  bool done() const { return options_.exit_with_sim && watch_.stopped(); }
  bool gave_up() const { return watch_.gave_up(); }
  // Set when the robot's joints do not fit the network.
  const std::string& error() const { return error_; }
  std::vector<std::string> TakeLog();
  const NnNodeCounters& counters() const { return counters_; }
  std::string Summary() const;

 private:
  void Log(std::string line);

  NnNodeOptions options_;
  MlpNetwork network_;
  NnObservation input_;  // reused each step
  bool announced_ = false;
  StatePacer pacer_;
  SimulatorWatch watch_;
  NnNodeCounters counters_;
  std::vector<std::string> log_;
  std::string error_;
};

}  // namespace mrsim
