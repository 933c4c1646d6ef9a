#include "sim_core/sim_process/sim_node.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/seq_gap.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/scene_object_state.h"

namespace mrsim {
namespace {

// Control requests remembered per sender for gap counting; beyond this the
// oldest senders are forgotten (every mrsim-ctl run is a sender of its own).
constexpr size_t kMaxControlSenders = 1000;
constexpr size_t kMaxNamedRefusedSenders = 4;

// The robots, then the loose parts (their servos on <prefix>_COMMAND_loose)
// as one more: commands to them pass the same filter.
std::vector<std::string> RobotNames(const Physics& physics) {
  std::vector<std::string> names;
  for (int r = 0; r < physics.robot_count(); ++r) {
    names.push_back(physics.robot_name(r));
  }
  if (physics.has_loose_parts()) names.push_back(kLooseOwnerName);
  return names;
}

std::vector<int> JointCounts(const Physics& physics) {
  std::vector<int> counts;
  for (int r = 0; r < physics.robot_count(); ++r) {
    counts.push_back(physics.joint_count(r));
  }
  if (physics.has_loose_parts()) counts.push_back(physics.loose_servo_count());
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
    case StopReason::kPhysicsFailed:
      return "physics failed";
  }
  return "?";
}

SimNode::SimNode(std::unique_ptr<Physics> physics, SimOptions options,
                 std::ostream& log, WallTime now)
    : physics_(std::move(physics)),
      options_(std::move(options)),
      log_(log),
      filter_(RobotNames(*physics_), JointCounts(*physics_)) {
  options_.Validate();
  const double dt = physics_->timestep();
  steps_per_period_ =
      std::max(1, static_cast<int>(std::lround(1.0 / (options_.rate * dt))));
  period_ = steps_per_period_ * dt;
  paused_ = options_.paused;
  pending_.resize(RobotNames(*physics_).size());
  last_status_ = wait_start_ = last_republish_ = anchor_ = now;
  last_status_sim_time_ = physics_->time();
}

void SimNode::Start(WallTime now, SimOutbox* out) {
  PublishStates(now, out);
  PublishStatus(now, out);
  Reanchor(now);
}

int64_t SimNode::AwaitedSeq() const {
  const int64_t seq = state_seq_ - options_.actuation_delay;
  return seq < epoch_seq_ ? -1 : seq;
}

bool SimNode::LockstepReady() const {
  const int64_t seq = AwaitedSeq();
  if (seq < 0) return true;
  return MissingControllers(seq).empty();
}

std::string SimNode::MissingControllers(int64_t seq) const {
  std::string names;
  const auto answers = answers_.find(seq);
  for (const std::string& c : options_.controllers) {
    bool done = false;
    if (answers != answers_.end()) {
      const auto answered = answers->second.answered.find(c);
      if (answered != answers->second.answered.end()) {
        done = true;
        const std::vector<bool>& robots = controller_robots_.at(c);
        for (size_t r = 0; r < robots.size(); ++r) {
          if (robots[r] && !answered->second[r]) done = false;
        }
      }
    }
    if (!done) names += (names.empty() ? "" : ",") + c;
  }
  return names;
}

WallTime SimNode::Tick(WallTime now, SimOutbox* out) {
  if (stopped_) return AfterSeconds(now, kIdleInterval);
  if (quit_) {
    Finish(StopReason::kQuit, now, out);
    return now;
  }
  if (options_.duration > 0 &&
      physics_->time() >= options_.duration - 0.5 * physics_->timestep()) {
    Finish(StopReason::kDuration, now, out);
    return now;
  }
  const bool idle_paused = paused_ && steps_pending_ == 0;
  WallTime status_due = AfterSeconds(last_status_, kStatusInterval);
  if (now >= status_due) {
    PublishStatus(now, out);
    if (idle_paused) ResendNewestStates(out);
    status_due = AfterSeconds(now, kStatusInterval);
  }
  const WallTime idle = std::min(status_due, AfterSeconds(now, kIdleInterval));
  if (idle_paused) return idle;

  switch (options_.clock) {
    case ClockMode::kLockstep:
      if (!LockstepReady()) {
        return std::min(idle, CheckLockstepWait(now, out));
      }
      break;
    case ClockMode::kRealtime: {
      const WallTime due = AfterSeconds(
          anchor_, periods_since_anchor_ * period_ / options_.speed);
      if (now < due) return std::min(idle, due);
      if (SecondsBetween(due, now) > kMaxLag) Reanchor(now);
      break;
    }
    case ClockMode::kFast:
      break;
  }
  RunPeriod(now, out);
  if (steps_pending_ > 0 && --steps_pending_ == 0) PublishStatus(now, out);
  return now;
}

WallTime SimNode::CheckLockstepWait(WallTime now, SimOutbox* out) {
  WallTime republish = AfterSeconds(last_republish_, kRepublishInterval);
  if (now >= republish) {
    ResendAwaitedStates(out);
    last_republish_ = now;
    republish = AfterSeconds(now, kRepublishInterval);
  }
  const double waited = SecondsBetween(wait_start_, now);
  const double next_warning =
      (timeout_warnings_ + 1) * options_.lockstep_timeout;
  if (waited < next_warning) {
    return std::min(republish, AfterSeconds(wait_start_, next_warning));
  }
  ++timeout_warnings_;
  const int64_t seq = AwaitedSeq();
  waiting_for_ = MissingControllers(seq);
  std::ostringstream line;
  line.precision(3);
  line << "mrsim-sim: lockstep: state seq " << seq << " (t=" << physics_->time()
       << " s) has waited " << waited << " s for controller(s) " << waiting_for_
       << "; still waiting";
  if (!refused_senders_.empty()) {
    line << "; commands from ";
    const char* sep = "";
    for (const std::string& sender : refused_senders_) {
      line << sep << "'" << sender << "'";
      sep = ", ";
    }
    line << " are refused: not among --controllers (";
    sep = "";
    for (const std::string& c : options_.controllers) {
      line << sep << c;
      sep = ",";
    }
    line << ")";
  }
  log_ << line.str() << std::endl;
  PublishStatus(now, out);
  return std::min(republish,
                  AfterSeconds(wait_start_, (timeout_warnings_ + 1) *
                                                options_.lockstep_timeout));
}

void SimNode::RunPeriod(WallTime now, SimOutbox* out) {
  if (!ran_period_) {
    ran_period_ = true;
    first_period_wall_ = now;
  }
  auto apply = [&](size_t r, const joint_command_t& cmd) {
    try {
      if (static_cast<int>(r) == physics_->robot_count()) {
        physics_->SetLooseTargets(cmd.target);  // the slot after the robots
      } else {
        physics_->SetJointTargets(static_cast<int>(r), cmd.target);
      }
      ++commands_applied_;
    } catch (const std::invalid_argument&) {
      ++rejected_value_;  // the filter should have caught it; never apply
    }
  };
  if (lockstep()) {
    const int64_t seq = AwaitedSeq();
    const auto answers = answers_.find(seq);
    if (answers != answers_.end()) {
      const std::vector<std::optional<joint_command_t>>& cmds =
          answers->second.command;
      for (size_t r = 0; r < cmds.size(); ++r) {
        if (cmds[r]) apply(r, *cmds[r]);
      }
    }
    answers_.erase(answers_.begin(), answers_.upper_bound(seq));
  } else {
    for (size_t r = 0; r < pending_.size(); ++r) {
      if (pending_[r]) apply(r, *pending_[r]);
      pending_[r].reset();
    }
  }
  try {
    physics_->Step(steps_per_period_);
  } catch (const PhysicsError& e) {
    // A batch run (--duration) has nobody to send RESET: it ends, and the
    // exit status says so.
    const bool batch = options_.duration > 0;
    Fail(std::string("physics: ") + e.what() +
         (batch ? " (run ended)" : " (paused; send RESET or LOAD_CHECKPOINT)"));
    log_ << "mrsim-sim: " << last_error_ << std::endl;
    if (batch) {
      Finish(StopReason::kPhysicsFailed, now, out);
      return;
    }
    paused_ = true;
    steps_pending_ = 0;
    PublishStatus(now, out);
    return;
  }
  steps_ += steps_per_period_;
  advanced_ += period_;
  ++periods_since_anchor_;
  PublishStates(now, out);
}

void SimNode::ResendAwaitedStates(SimOutbox* out) {
  // Every state still awaited, oldest first (pipelined: two of them).
  for (const Published& p : recent_) {
    for (const auto& [channel, msg] : p.messages) out->Add(channel, msg);
    ++states_resent_;
  }
}

void SimNode::ResendNewestStates(SimOutbox* out) {
  if (!options_.publish_state || state_seq_ < 0) return;
  if (lockstep()) {
    ResendAwaitedStates(out);
    return;
  }
  // Realtime and fast keep no copy of what they sent (one per period would
  // cost more than this): paused physics still reads as the newest state.
  for (auto& [channel, msg] : ReadStates().messages) {
    out->Add(std::move(channel), std::move(msg));
  }
  ++states_resent_;
}

SimNode::Published SimNode::ReadStates() const {
  Published published{state_seq_, {}};
  // Scene first: a viewer draws a frame once a robot state reaches its
  // time, so the scene of that period must already be there.
  const std::vector<SceneObjectState> scene = ReadSceneObjects(*physics_);
  if (!scene.empty()) {
    published.messages.emplace_back(
        SceneChannel(options_.prefix),
        ToSceneStateMessage(scene, physics_->time(), state_seq_));
  }
  // The parts outside any robot, as a robot_state_t of the owner "loose",
  // so every reader of robot states (logger, Python, camera) reads them.
  if (physics_->has_loose_parts()) {
    robot_state_t msg =
        ToRobotStateMessage(physics_->ReadLooseState(), state_seq_);
    SetLockStates(physics_->LockStates(kLooseOwnerName), &msg);
    published.messages.emplace_back(
        StateChannel(options_.prefix, kLooseOwnerName), std::move(msg));
  }
  for (int r = 0; r < physics_->robot_count(); ++r) {
    const std::string& name = physics_->robot_name(r);
    robot_state_t msg =
        ToRobotStateMessage(physics_->ReadRobotState(r), state_seq_);
    SetLockStates(physics_->LockStates(name), &msg);
    published.messages.emplace_back(StateChannel(options_.prefix, name),
                                    std::move(msg));
  }
  return published;
}

void SimNode::PublishStates(WallTime now, SimOutbox* out) {
  ++state_seq_;
  Published published{state_seq_, {}};
  if (options_.publish_state) {
    published = ReadStates();
    ++states_published_;
  }
  if (lockstep()) {
    for (const auto& [channel, msg] : published.messages) {
      out->Add(channel, msg);
    }
    // Keep what may have to be sent again: the states still awaited.
    recent_.push_back(std::move(published));
    while (!recent_.empty() &&
           recent_.front().seq < state_seq_ - options_.actuation_delay) {
      recent_.pop_front();
    }
  } else {
    for (auto& [channel, msg] : published.messages) {
      out->Add(std::move(channel), std::move(msg));
    }
  }
  wait_start_ = last_republish_ = now;
  timeout_warnings_ = 0;
  waiting_for_.clear();
}

sim_status_t SimNode::status() const {
  sim_status_t s{};
  s.utime = SimTimeToUtime(physics_->time());
  s.seq = status_seq_;
  s.sim_time = physics_->time();
  s.real_time_factor = real_time_factor_;
  // lcm-gen's constants are declared, not defined: copy, never bind.
  if (quit_ || stopped_) {
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
  s.states_published = states_published_;
  s.actuation_delay = options_.actuation_delay;
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
  s.control_sender = control_sender_;
  s.control_ok = control_ok_;
  s.waiting_for = waiting_for_;
  s.last_error = last_error_;
  s.instance = options_.instance;
  return s;
}

void SimNode::OnSimStatus(const sim_status_t& status) {
  if (status.instance == options_.instance) return;
  // A status without an instance comes from an older mrsim-sim: still
  // another simulator, but one that cannot be told apart from others.
  const std::string who = status.instance.empty() ? "?" : status.instance;
  if (!other_simulators_.insert(who).second) return;
  log_ << "mrsim-sim: warning: another simulator (" << who << ", "
       << status.clock << " clock, sim time " << status.sim_time
       << " s) publishes on " << SimStatusChannel(options_.prefix)
       << ": both take the commands and controls sent there (stop one, or "
          "give one another --prefix or --lcm-url)"
       << std::endl;
}

void SimNode::PublishStatus(WallTime now, SimOutbox* out) {
  const double wall = SecondsBetween(last_status_, now);
  if (wall > 0.05) {
    real_time_factor_ =
        std::max(0.0, (physics_->time() - last_status_sim_time_) / wall);
    last_status_sim_time_ = physics_->time();
  }
  last_status_ = now;
  out->Add(SimStatusChannel(options_.prefix), status());
  ++status_seq_;
}

void SimNode::Reanchor(WallTime now) {
  anchor_ = now;
  periods_since_anchor_ = 0;
}

void SimNode::ClearPending() {
  for (auto& p : pending_) {
    if (p) ++superseded_;
    p.reset();
  }
  for (const auto& [seq, answers] : answers_) {
    for (const auto& c : answers.command) {
      if (c) ++superseded_;
    }
  }
  answers_.clear();
}

void SimNode::Restarted(WallTime now, SimOutbox* out) {
  ClearPending();
  recent_.clear();
  last_status_sim_time_ = physics_->time();
  epoch_seq_ = state_seq_ + 1;
  PublishStates(now, out);
}

void SimNode::Fail(const std::string& error) {
  last_error_ = error;
  control_ok_ = false;
}

void SimNode::OnMalformed(const std::string& what) {
  ++malformed_;
  if (!what.empty()) last_error_ = what;
}

void SimNode::OnCommand(const joint_command_t& cmd, const std::string& channel,
                        WallTime /*now*/) {
  const std::string command_prefix = CommandChannel(options_.prefix, "");
  const std::string channel_robot =
      channel.compare(0, command_prefix.size(), command_prefix) == 0
          ? channel.substr(command_prefix.size())
          : std::string();
  // Answers are kept for every state still to be awaited: with a delay,
  // those published before the first one awaited too.
  const int64_t oldest =
      std::max(state_seq_ - options_.actuation_delay, epoch_seq_);
  const CommandVerdict verdict = filter_.Check(
      cmd, channel_robot, state_seq_, lockstep(), options_.controllers, oldest);
  switch (verdict) {
    case CommandVerdict::kAccepted:
      break;
    case CommandVerdict::kWrongJointCount:
      ++rejected_joint_count_;
      if (channel_robot == kLooseOwnerName) {
        // The counter alone would not tell a passive hinge from a miscount.
        const int servos = physics_->loose_servo_count();
        last_error_ =
            servos == 0
                ? "COMMAND_loose: the loose parts have no servo (their "
                  "hinges are passive; give one <servo>true</servo>), "
                  "command dropped"
                : "COMMAND_loose: expected " + std::to_string(servos) +
                      " targets (one per loose servo), got " +
                      std::to_string(cmd.num_joints) + "; command dropped";
      }
      return;
    case CommandVerdict::kBadValue:
      ++rejected_value_;
      return;
    case CommandVerdict::kUnknownRobot:
      ++rejected_robot_;
      if (channel_robot == kLooseOwnerName && !physics_->has_loose_parts()) {
        last_error_ =
            "COMMAND_loose: the scenario has no loose parts; command dropped";
      }
      return;
    case CommandVerdict::kStaleSeq:
      ++rejected_seq_;
      return;
    case CommandVerdict::kRepeat:
      ++repeated_commands_;
      return;
    case CommandVerdict::kEmptyIgnored:
      ++empty_answers_;
      return;
    case CommandVerdict::kNotController:
      ++rejected_sender_;
      if (refused_senders_.size() < kMaxNamedRefusedSenders) {
        refused_senders_.insert(cmd.sender);
      }
      return;
  }
  const int r = filter_.robot_index(cmd.robot);
  if (!lockstep()) {
    if (pending_[r]) ++superseded_;
    pending_[r] = cmd;
    return;
  }
  const size_t n = pending_.size();
  const int controller =
      static_cast<int>(std::find(options_.controllers.begin(),
                                 options_.controllers.end(), cmd.sender) -
                       options_.controllers.begin());
  auto& robots = controller_robots_[cmd.sender];
  robots.resize(n, false);
  robots[r] = true;
  Answers& answers = answers_[cmd.state_seq];
  answers.command.resize(n);
  answers.controller.resize(n, -1);
  auto& answered = answers.answered[cmd.sender];
  answered.resize(n, false);
  answered[r] = true;
  if (cmd.num_joints == 0) {
    // An answer that moves nothing (mrsim-camera): the state is answered,
    // a real controller's command for it still applies.
    ++empty_answers_;
    return;
  }
  if (answers.command[r]) {
    ++superseded_;
    // When several controllers drive one robot, the one listed last in
    // --controllers wins, whatever the arrival order.
    if (controller < answers.controller[r]) return;
  }
  answers.command[r] = cmd;
  answers.controller[r] = controller;
}

void SimNode::OnControl(const sim_control_t& msg, WallTime now,
                        SimOutbox* out) {
  // The acknowledgement goes before anything the request publishes (the
  // new state after RESET or LOAD_CHECKPOINT), so a controller knows of
  // the load before it sees the state it has to answer.
  const size_t first = out->messages.size();
  try {
    auto last = control_last_seq_.find(msg.sender);
    if (last != control_last_seq_.end()) {
      control_gaps_ += SeqGap(last->second, msg.seq);  // overflow-safe
    }
    if (last == control_last_seq_.end() &&
        control_last_seq_.size() >= kMaxControlSenders) {
      control_last_seq_.erase(control_last_seq_.begin());
    }
    control_last_seq_[msg.sender] = msg.seq;
    control_seq_ = msg.seq;
    control_sender_ = msg.sender;
    control_ok_ = true;

    switch (msg.command) {
      case sim_control_t::PAUSE:
        paused_ = true;
        steps_pending_ = 0;
        break;
      case sim_control_t::RESUME:
        paused_ = false;
        steps_pending_ = 0;
        Reanchor(now);
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
        Restarted(now, out);
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
          Restarted(now, out);
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
        Reanchor(now);
        break;
      case sim_control_t::QUIT:
        quit_ = true;
        break;
      case sim_control_t::DETACH:
      case sim_control_t::ATTACH:
        try {
          // Acts from the next period; its state shows the lock's flag.
          physics_->SetLockAttached(msg.robot, msg.lock,
                                    msg.command == sim_control_t::ATTACH);
        } catch (const PhysicsError& e) {
          Fail(std::string(msg.command == sim_control_t::ATTACH ? "ATTACH"
                                                                : "DETACH") +
               ": " + e.what());
        }
        break;
      default:
        Fail("unknown sim_control_t command " + std::to_string(msg.command));
        break;
    }
  } catch (const std::exception& e) {
    Fail(std::string("control: ") + e.what());
  }
  PublishStatus(now, out);
  std::rotate(out->messages.begin() + static_cast<std::ptrdiff_t>(first),
              out->messages.end() - 1, out->messages.end());
}

void SimNode::Stop(StopReason reason, WallTime now, SimOutbox* out) {
  if (!stopped_) Finish(reason, now, out);
}

void SimNode::Finish(StopReason reason, WallTime now, SimOutbox* out) {
  // A failed state is not worth keeping over a good checkpoint file.
  if (!options_.checkpoint_on_exit.empty() &&
      reason != StopReason::kPhysicsFailed) {
    try {
      SaveCheckpoint(options_.checkpoint_on_exit);
    } catch (const std::exception& e) {
      Fail(e.what());
      exit_checkpoint_error_ = e.what();
      log_ << "mrsim-sim: --checkpoint-on-exit: " << e.what() << std::endl;
    }
  }
  quit_ = true;
  stopped_ = reason;
  end_wall_ = now;
  PublishStatus(now, out);
}

void SimNode::SaveCheckpoint(const std::string& path) const {
  if (path.empty()) throw std::runtime_error("checkpoint: empty path");
  mrsim::SaveCheckpoint(path, *physics_);
}

void SimNode::LoadCheckpoint(const std::string& path) {
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

std::string SimNode::Summary() const {
  const sim_status_t s = status();
  std::ostringstream out;
  out << "mrsim-sim: stopped ("
      << (stopped_ ? ToString(*stopped_) : "still running") << ") at sim time "
      << s.sim_time << " s after " << s.steps << " steps; states published "
      << states_published_;
  if (states_resent_ > 0) out << " (re-sent " << states_resent_ << ")";
  out << "; commands applied " << s.commands_applied;
  if (repeated_commands_ > 0) {
    out << " (" << repeated_commands_ << " repeats ignored)";
  }
  if (empty_answers_ > 0) {
    out << " (" << empty_answers_ << " answers without targets)";
  }
  out << ", rejected " << s.commands_rejected << " (joint count "
      << s.rejected_joint_count << ", value " << s.rejected_value << ", robot "
      << s.rejected_robot << ", seq " << s.rejected_seq << ", sender "
      << s.rejected_sender << "), malformed " << s.messages_malformed
      << ", dropped " << s.messages_dropped;
  if (s.messages_dropped > 0) {
    // A newer command taking an older one's place is not a loss: a
    // controller faster than the simulator (or a burst) does it.
    out << " (" << filter_.seq_gaps() + control_gaps_ << " never arrived, "
        << superseded_ << " replaced by a newer one before use)";
  }
  if (ran_period_) {
    // Whole-run pace, from the first period to the last (startup and the
    // wait for the first lockstep answer excluded).
    const double wall = SecondsBetween(first_period_wall_, end_wall_);
    if (wall > 0) out << "; real-time factor " << advanced_ / wall;
  }
  return out.str();
}

}  // namespace mrsim
