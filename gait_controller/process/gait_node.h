// The LCM side of mrsim-gait: answers each state of one robot with joint
// targets from a GaitController, using the state's sim time as the clock so
// a lockstep run equals RunGait in process, and takes gait_command_t
// changes. Holds the lcm::LCM by reference; main owns it.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/gait_controller.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"

namespace mrsim {

struct GaitNodeOptions {
  std::string robot;
  std::string prefix = "MRSIM";
  std::string sender;  // joint_command_t.sender
  // Hz of sim time: states closer together than 1/rate are not answered
  // (0: answer every state). If the simulator sends a skipped state again
  // (lockstep waiting for it), the node answers it and every state after.
  double rate = 100.0;
  GaitControllerOptions controller;
};

struct GaitNodeCounters {
  int64_t states_answered = 0;
  int64_t states_repeated = 0;  // same seq again: the last answer re-sent
  int64_t states_skipped = 0;   // closer than 1/rate, or older than the last
  int64_t states_foreign = 0;   // another robot's
  int64_t messages_malformed = 0;
  int64_t commands_applied = 0;
  int64_t commands_rejected = 0;
};

class GaitNode {
 public:
  // axes_for(joint_count) gives the hinge axes once the first state says
  // how many joints there are; it may throw std::invalid_argument, which
  // makes the node fail (see error()). Subscribes STATE_<robot> and
  // GAIT_<robot>. Throws std::runtime_error if LCM cannot subscribe.
  GaitNode(lcm::LCM& lcm, GaitNodeOptions options,
           std::function<std::vector<Axis>(int)> axes_for, Gait initial);
  ~GaitNode();
  GaitNode(const GaitNode&) = delete;
  GaitNode& operator=(const GaitNode&) = delete;

  // Applies a gait command from any source (LCM, keyboard) all or nothing;
  // before the first state it is queued. Never throws: a bad command is
  // counted and logged.
  void Apply(const gait_command_t& command, const std::string& source);

  // Lines to print (changes, rejections) since the last call.
  std::vector<std::string> TakeLog();
  // Set when the node cannot go on (the joint axes do not fit the robot).
  const std::string& error() const { return error_; }
  const GaitNodeCounters& counters() const { return counters_; }
  // Null until the first state arrived.
  const GaitController* controller() const { return controller_.get(); }
  std::string Describe() const;

 private:
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void OnGait(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void HandleState(const robot_state_t& state);
  void Log(std::string line);

  lcm::LCM& lcm_;
  GaitNodeOptions options_;
  std::function<std::vector<Axis>(int)> axes_for_;
  Gait initial_;
  std::vector<lcm::Subscription*> subscriptions_;
  std::unique_ptr<GaitController> controller_;
  std::deque<std::pair<gait_command_t, std::string>> queued_;

  double rate_ = 0;  // options_.rate until lockstep shows it must be 0
  int64_t last_skipped_seq_ = -1;
  bool have_last_ = false;
  int64_t last_state_seq_ = -1;
  double last_time_ = 0;
  joint_command_t last_command_;
  int64_t command_seq_ = 0;

  GaitNodeCounters counters_;
  std::vector<std::string> log_;
  std::string error_;
};

}  // namespace mrsim
