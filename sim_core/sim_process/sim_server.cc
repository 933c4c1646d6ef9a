#include "sim_core/sim_process/sim_server.h"

#include <glib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "common/wall_time.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "sim_core/checkpoint.h"
#include "sim_core/sim_process/state_message.h"

namespace mrsim {
namespace {

// While a lockstep period waits, the state is sent again this often so a
// controller that started late (or lost the packet) still gets it.
constexpr double kRepublishInterval = 0.25;  // s, wall
constexpr double kStatusInterval = 0.5;      // s, wall (about 2 Hz)
// Realtime: a period later than this is not caught up with a burst.
constexpr double kMaxLag = 0.25;  // s, wall

std::string EscapeRegex(const std::string& text) {
  std::unique_ptr<gchar, decltype(&g_free)> escaped(
      g_regex_escape_string(text.c_str(), static_cast<gint>(text.size())),
      &g_free);
  return escaped.get();
}

std::vector<std::string> RobotNames(const Physics& physics) {
  std::vector<std::string> names;
  for (int r = 0; r < physics.robot_count(); ++r) {
    names.push_back(physics.robot_name(r));
  }
  return names;
}

std::vector<int> JointCounts(const Physics& physics) {
  std::vector<int> counts;
  for (int r = 0; r < physics.robot_count(); ++r) {
    counts.push_back(physics.joint_count(r));
  }
  return counts;
}

}  // namespace

const char* ToString(StopReason reason) {
  switch (reason) {
    case StopReason::kQuit:
      return "quit requested";
    case StopReason::kDuration:
      return "duration reached";
    case StopReason::kSignal:
      return "stop signal";
  }
  return "?";
}

SimServer::SimServer(lcm::LCM& lcm, std::unique_ptr<Physics> physics,
                     SimOptions options, std::ostream& log)
    : lcm_(lcm),
      physics_(std::move(physics)),
      options_(std::move(options)),
      log_(log),
      filter_(RobotNames(*physics_), JointCounts(*physics_)) {
  options_.Validate();
  const double dt = physics_->timestep();
  steps_per_period_ =
      std::max(1, static_cast<int>(std::lround(1.0 / (options_.rate * dt))));
  period_ = steps_per_period_ * dt;
  paused_ = options_.paused;
  pending_.resize(physics_->robot_count());
  pending_controller_.assign(physics_->robot_count(), -1);

  lcm::Subscription* commands =
      lcm_.subscribe(EscapeRegex(CommandChannel(options_.prefix, "")) + ".*",
                     &SimServer::OnCommand, this);
  lcm::Subscription* control = lcm_.subscribe(
      SimControlChannel(options_.prefix), &SimServer::OnControl, this);
  if (commands == nullptr || control == nullptr) {
    throw std::runtime_error("cannot subscribe to the LCM channels");
  }
  commands->setQueueCapacity(kCommandQueueCapacity);
  control->setQueueCapacity(kControlQueueCapacity);
  subscriptions_ = {commands, control};
  last_status_ = Clock::now();
  last_status_sim_time_ = physics_->time();
}

SimServer::~SimServer() {
  for (lcm::Subscription* s : subscriptions_) lcm_.unsubscribe(s);
}

StopReason SimServer::Run(const std::function<bool()>& stop_requested) {
  PublishStates();
  PublishStatus();
  Reanchor();
  const bool lockstep = options_.clock == ClockMode::kLockstep;
  StopReason reason = StopReason::kQuit;
  while (true) {
    if (quit_) {
      reason = StopReason::kQuit;
      break;
    }
    if (stop_requested()) {
      reason = StopReason::kSignal;
      break;
    }
    if (options_.duration > 0 &&
        physics_->time() >= options_.duration - 0.5 * physics_->timestep()) {
      reason = StopReason::kDuration;
      break;
    }
    if (paused_ && steps_pending_ == 0) {
      Handle(50);
      MaybePublishStatus();
      continue;
    }
    if (lockstep) {
      Handle(0);
      if (!LockstepAnswered()) {
        Handle(10);
        if (!LockstepAnswered()) {
          CheckLockstepWait();
          MaybePublishStatus();
          continue;
        }
      }
    } else if (options_.clock == ClockMode::kRealtime) {
      const auto due =
          anchor_ + std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>(
                            periods_since_anchor_ * period_ / options_.speed));
      const auto now = Clock::now();
      if (now < due) {
        const double wait_ms = Seconds(due - now) * 1e3;
        Handle(std::min(50, static_cast<int>(std::ceil(wait_ms))));
        MaybePublishStatus();
        continue;
      }
      if (Seconds(now - due) > kMaxLag) Reanchor();
    } else {
      Handle(0);
    }
    if (paused_ && steps_pending_ == 0) continue;  // a PAUSE just arrived
    RunPeriod();
    if (steps_pending_ > 0 && --steps_pending_ == 0) PublishStatus();
    MaybePublishStatus();
  }

  if (!options_.checkpoint_on_exit.empty()) {
    try {
      SaveCheckpoint(options_.checkpoint_on_exit);
    } catch (const std::exception& e) {
      Fail(e.what());
      exit_checkpoint_error_ = e.what();
      log_ << "mrsim-sim: --checkpoint-on-exit: " << e.what() << std::endl;
    }
  }
  quit_ = true;
  run_end_wall_ = Clock::now();
  PublishStatus();
  return reason;
}

void SimServer::Handle(int timeout_ms) { HandleFor(lcm_, timeout_ms); }

bool SimServer::LockstepAnswered() const {
  for (const std::string& c : options_.controllers) {
    auto answered = answered_.find(c);
    if (answered == answered_.end()) return false;
    const std::vector<bool>& robots = controller_robots_.at(c);
    for (size_t r = 0; r < robots.size(); ++r) {
      if (robots[r] && !answered->second[r]) return false;
    }
  }
  return true;
}

void SimServer::CheckLockstepWait() {
  const auto now = Clock::now();
  if (Seconds(now - last_republish_) >= kRepublishInterval) {
    SendStates();
    last_republish_ = now;
  }
  const double waited = Seconds(now - wait_start_);
  if (waited < (timeout_warnings_ + 1) * options_.lockstep_timeout) return;
  ++timeout_warnings_;
  std::string names;
  for (const std::string& c : options_.controllers) {
    bool done = answered_.count(c) > 0;
    if (done) {
      const std::vector<bool>& robots = controller_robots_.at(c);
      const std::vector<bool>& answered = answered_.at(c);
      for (size_t r = 0; r < robots.size(); ++r) {
        if (robots[r] && !answered[r]) done = false;
      }
    }
    if (!done) names += (names.empty() ? "" : ",") + c;
  }
  waiting_for_ = names;
  std::ostringstream line;
  line.precision(3);
  line << "mrsim-sim: lockstep: state seq " << state_seq_
       << " (t=" << physics_->time() << " s) has waited " << waited
       << " s for controller(s) " << names << "; still waiting";
  log_ << line.str() << std::endl;
  PublishStatus();
}

void SimServer::RunPeriod() {
  if (!ran_period_) {
    ran_period_ = true;
    first_period_wall_ = Clock::now();
  }
  for (size_t r = 0; r < pending_.size(); ++r) {
    if (!pending_[r]) continue;
    try {
      physics_->SetJointTargets(static_cast<int>(r), pending_[r]->target);
      ++commands_applied_;
    } catch (const std::invalid_argument&) {
      ++rejected_value_;  // the filter should have caught it; never apply
    }
    pending_[r].reset();
    pending_controller_[r] = -1;
  }
  try {
    physics_->Step(steps_per_period_);
  } catch (const PhysicsError& e) {
    Fail(std::string("physics: ") + e.what() +
         " (paused; send RESET or LOAD_CHECKPOINT)");
    log_ << "mrsim-sim: " << last_error_ << std::endl;
    paused_ = true;
    steps_pending_ = 0;
    PublishStatus();
    return;
  }
  steps_ += steps_per_period_;
  advanced_ += period_;
  ++periods_since_anchor_;
  PublishStates();
}

void SimServer::PublishStates() {
  ++state_seq_;
  SendStates();
  answered_.clear();
  wait_start_ = last_republish_ = Clock::now();
  timeout_warnings_ = 0;
  waiting_for_.clear();
}

void SimServer::SendStates() {
  if (!options_.publish_state) return;
  // Scene first: a viewer draws a frame once a robot state reaches its time,
  // so the scene of that period must already be there.
  const std::vector<SceneObjectState> scene = ReadSceneObjects(*physics_);
  if (!scene.empty()) {
    const scene_state_t msg =
        ToSceneStateMessage(scene, physics_->time(), state_seq_);
    lcm_.publish(SceneChannel(options_.prefix), &msg);
  }
  for (int r = 0; r < physics_->robot_count(); ++r) {
    const robot_state_t msg =
        ToRobotStateMessage(physics_->ReadRobotState(r), state_seq_);
    lcm_.publish(StateChannel(options_.prefix, physics_->robot_name(r)), &msg);
  }
}

sim_status_t SimServer::status() const {
  sim_status_t s{};
  s.utime = SimTimeToUtime(physics_->time());
  s.seq = status_seq_;
  s.sim_time = physics_->time();
  s.real_time_factor = real_time_factor_;
  // lcm-gen's constants are declared, not defined: copy, never bind.
  if (quit_) {
    s.mode = sim_status_t::STOPPING;
  } else if (paused_ && steps_pending_ == 0) {
    s.mode = sim_status_t::PAUSED;
  } else {
    s.mode = sim_status_t::RUNNING;
  }
  s.clock = ToString(options_.clock);
  s.speed = options_.speed;
  s.control_rate = 1.0 / period_;
  s.steps_per_period = steps_per_period_;
  s.steps = steps_;
  s.state_seq = state_seq_;
  s.commands_applied = commands_applied_;
  s.rejected_joint_count = rejected_joint_count_;
  s.rejected_value = rejected_value_;
  s.rejected_robot = rejected_robot_;
  s.rejected_seq = rejected_seq_;
  s.rejected_sender = rejected_sender_;
  s.commands_rejected = rejected_joint_count_ + rejected_value_ +
                        rejected_robot_ + rejected_seq_ + rejected_sender_;
  s.messages_malformed = malformed_;
  s.messages_dropped = filter_.seq_gaps() + superseded_ + control_gaps_;
  s.control_seq = control_seq_;
  s.control_ok = control_ok_;
  s.waiting_for = waiting_for_;
  s.last_error = last_error_;
  return s;
}

void SimServer::PublishStatus() {
  const auto now = Clock::now();
  const double wall = Seconds(now - last_status_);
  if (wall > 0.05) {
    real_time_factor_ =
        std::max(0.0, (physics_->time() - last_status_sim_time_) / wall);
    last_status_ = now;
    last_status_sim_time_ = physics_->time();
  }
  const sim_status_t s = status();
  lcm_.publish(SimStatusChannel(options_.prefix), &s);
  ++status_seq_;
}

void SimServer::MaybePublishStatus() {
  if (Seconds(Clock::now() - last_status_) >= kStatusInterval) {
    PublishStatus();
  }
}

void SimServer::Reanchor() {
  anchor_ = Clock::now();
  periods_since_anchor_ = 0;
}

void SimServer::ClearPending() {
  for (auto& p : pending_) {
    if (p) ++superseded_;
    p.reset();
  }
  pending_controller_.assign(pending_.size(), -1);
}

void SimServer::Fail(const std::string& error) {
  last_error_ = error;
  control_ok_ = false;
}

// LCM calls the handlers from C: nothing may escape them.
void SimServer::OnCommand(const lcm::ReceiveBuffer* rbuf,
                          const std::string& channel) {
  try {
    joint_command_t cmd;
    if (!DecodeMessage(rbuf, &cmd)) {
      ++malformed_;
      return;
    }
    HandleCommand(cmd, channel);
  } catch (const std::exception& e) {
    ++malformed_;  // e.g. an absurd array length in a forged message
    last_error_ = std::string("command on ") + channel + ": " + e.what();
  } catch (...) {
    ++malformed_;
  }
}

void SimServer::HandleCommand(const joint_command_t& cmd,
                              const std::string& channel) {
  const std::string channel_robot =
      channel.substr(CommandChannel(options_.prefix, "").size());
  const bool lockstep = options_.clock == ClockMode::kLockstep;
  const CommandVerdict verdict = filter_.Check(cmd, channel_robot, state_seq_,
                                               lockstep, options_.controllers);
  switch (verdict) {
    case CommandVerdict::kAccepted:
      break;
    case CommandVerdict::kWrongJointCount:
      ++rejected_joint_count_;
      return;
    case CommandVerdict::kBadValue:
      ++rejected_value_;
      return;
    case CommandVerdict::kUnknownRobot:
      ++rejected_robot_;
      return;
    case CommandVerdict::kStaleSeq:
      ++rejected_seq_;
      return;
    case CommandVerdict::kNotController:
      ++rejected_sender_;
      return;
  }
  const int r = filter_.robot_index(cmd.robot);
  int controller = -1;
  if (lockstep) {
    controller =
        static_cast<int>(std::find(options_.controllers.begin(),
                                   options_.controllers.end(), cmd.sender) -
                         options_.controllers.begin());
    const size_t n = pending_.size();
    auto& robots = controller_robots_[cmd.sender];
    robots.resize(n, false);
    robots[r] = true;
    auto& answered = answered_[cmd.sender];
    answered.resize(n, false);
    answered[r] = true;
  }
  if (pending_[r]) {
    ++superseded_;
    // Lockstep: when several controllers drive one robot, the one listed
    // last in --controllers wins, whatever the arrival order.
    if (lockstep && controller < pending_controller_[r]) return;
  }
  pending_[r] = cmd;
  pending_controller_[r] = controller;
}

void SimServer::OnControl(const lcm::ReceiveBuffer* rbuf,
                          const std::string& /*channel*/) {
  try {
    HandleControl(rbuf);
  } catch (const std::exception& e) {
    Fail(std::string("control: ") + e.what());
    try {
      PublishStatus();
    } catch (...) {
    }
  } catch (...) {
    Fail("control: unknown error");
  }
}

void SimServer::HandleControl(const lcm::ReceiveBuffer* rbuf) {
  sim_control_t msg;
  if (!DecodeMessage(rbuf, &msg)) {
    ++malformed_;
    return;
  }
  auto last = control_last_seq_.find(msg.sender);
  if (last != control_last_seq_.end() && msg.seq > last->second + 1) {
    control_gaps_ += msg.seq - last->second - 1;
  }
  control_last_seq_[msg.sender] = msg.seq;
  control_seq_ = msg.seq;
  control_ok_ = true;

  switch (msg.command) {
    case sim_control_t::PAUSE:
      paused_ = true;
      steps_pending_ = 0;
      break;
    case sim_control_t::RESUME:
      paused_ = false;
      steps_pending_ = 0;
      Reanchor();
      break;
    case sim_control_t::STEP:
      if (msg.steps < 1) {
        Fail("STEP: steps must be >= 1, got " + std::to_string(msg.steps));
        break;
      }
      paused_ = true;
      steps_pending_ += msg.steps;
      break;
    case sim_control_t::RESET:
      // A fresh build, not Physics::Reset: MuJoCo keeps solver scratch
      // between steps that a reset in place does not clear.
      physics_ = std::make_unique<Physics>(physics_->scenario());
      ClearPending();
      last_status_sim_time_ = physics_->time();
      PublishStates();
      break;
    case sim_control_t::SAVE_CHECKPOINT:
      try {
        SaveCheckpoint(msg.path);
      } catch (const std::exception& e) {
        Fail(e.what());
      }
      break;
    case sim_control_t::LOAD_CHECKPOINT:
      try {
        LoadCheckpoint(msg.path);
        ClearPending();
        last_status_sim_time_ = physics_->time();
        PublishStates();
      } catch (const std::exception& e) {
        Fail(e.what());
      }
      break;
    case sim_control_t::SET_SPEED:
      if (!(std::isfinite(msg.speed) && msg.speed > 0)) {
        Fail("SET_SPEED: speed must be a number > 0");
        break;
      }
      options_.speed = msg.speed;
      Reanchor();
      break;
    case sim_control_t::QUIT:
      quit_ = true;
      break;
    default:
      Fail("unknown sim_control_t command " + std::to_string(msg.command));
      break;
  }
  PublishStatus();
}

void SimServer::SaveCheckpoint(const std::string& path) const {
  if (path.empty()) throw std::runtime_error("checkpoint: empty path");
  mrsim::SaveCheckpoint(path, *physics_);
}

void SimServer::LoadCheckpoint(const std::string& path) {
  std::unique_ptr<Physics> loaded = mrsim::LoadCheckpoint(path);
  // The running process keeps its robots and channels, so only a checkpoint
  // of the same scenario can be loaded into it.
  Scenario mine = physics_->scenario();
  Scenario theirs = loaded->scenario();
  mine.base_dir.clear();
  theirs.base_dir.clear();
  if (!(mine == theirs)) {
    throw std::runtime_error("checkpoint: " + path +
                             " holds a different scenario than the one "
                             "running; start mrsim-sim with --load-checkpoint");
  }
  // Swap in the fresh Physics rather than LoadState into the running one,
  // whose leftover solver scratch would differ in the last bits from a
  // process started with --load-checkpoint.
  physics_ = std::move(loaded);
}

std::string SimServer::Summary(StopReason reason) const {
  const sim_status_t s = status();
  std::ostringstream out;
  out << "mrsim-sim: stopped (" << ToString(reason) << ") at sim time "
      << s.sim_time << " s after " << s.steps << " steps; states published "
      << state_seq_ + 1 << "; commands applied " << s.commands_applied
      << ", rejected " << s.commands_rejected << " (joint count "
      << s.rejected_joint_count << ", value " << s.rejected_value << ", robot "
      << s.rejected_robot << ", seq " << s.rejected_seq << ", sender "
      << s.rejected_sender << "), malformed " << s.messages_malformed
      << ", dropped " << s.messages_dropped;
  if (ran_period_) {
    // Whole-run pace, from the first period on (startup and the wait for
    // the first lockstep answer excluded).
    const double wall = Seconds(run_end_wall_ - first_period_wall_);
    if (wall > 0) {
      out << "; real-time factor " << advanced_ / wall;
    }
  }
  return out.str();
}

}  // namespace mrsim
