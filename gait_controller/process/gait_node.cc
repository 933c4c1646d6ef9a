#include "gait_controller/process/gait_node.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/exact_number.h"
#include "gait_controller/cpg_feedback.h"
#include "gait_controller/process/gait_command_apply.h"
#include "gait_controller/process/gait_parameters_message.h"
#include "gait_controller/process/motion_fit.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/usage_error.h"

namespace mrsim {

namespace {

Eigen::Vector3d Position(const pose_t& pose) {
  return Eigen::Vector3d(pose.position[0], pose.position[1], pose.position[2]);
}

}  // namespace

void GaitNode::FeedSensors(const robot_state_t& state) {
  // A CPG gait with feedback takes the sensor modules' readings
  // (docs/gait.md, "Sensory feedback"); anything else ignores them.
  const std::optional<CpgParameters>& cpg = controller_->active_gait().cpg;
  if (!cpg || cpg->feedback_gain == 0) return;
  RobotState s;
  s.joints.resize(state.joints.size());
  for (size_t j = 0; j < state.joints.size(); ++j) {
    s.joints[j].world.position = Position(state.joints[j].world);
  }
  s.sensor_modules.resize(state.sensor_modules.size());
  for (size_t k = 0; k < state.sensor_modules.size(); ++k) {
    const sensor_module_state_t& m = state.sensor_modules[k];
    SensorModuleState& out = s.sensor_modules[k];
    out.pose.position = Position(m.pose);
    out.has_force = m.has_force && std::isfinite(m.force);
    out.force = out.has_force ? m.force : 0.0;
    for (double d : m.distance) {
      if (std::isfinite(d)) out.distances.push_back(d);
    }
  }
  controller_->SetFeedback(CpgFeedback(s, *cpg));
}

namespace {

constexpr size_t kMaxQueued = 100;
constexpr size_t kMaxSnapshots = 256;
constexpr size_t kMaxRequests = 64;
constexpr const char* kCheckpointTag = "mrsim-gait-checkpoint-1";

constexpr size_t kMaxLogLines = 1000;

}  // namespace

std::string GaitCheckpointPath(const std::string& checkpoint,
                               const std::string& robot) {
  return checkpoint + ".gait-" + robot;
}

GaitNode::GaitNode(GaitNodeOptions options,
                   std::function<std::vector<Axis>(int)> axes_for, Gait initial,
                   WallTime now)
    : options_(std::move(options)),
      axes_for_(std::move(axes_for)),
      initial_(std::move(initial)),
      pacer_(options_.robot, options_.sender, options_.rate),
      watch_(
          fmt::format("{} or {}", StateChannel(options_.prefix, options_.robot),
                      SimStatusChannel(options_.prefix)),
          options_.exit_with_sim, now),
      last_status_(now) {}

void GaitNode::Log(std::string line) {
  if (log_.size() < kMaxLogLines) log_.push_back(std::move(line));
}

std::vector<std::string> GaitNode::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

std::string GaitNode::Describe() const {
  if (!controller_) {
    std::string queued;
    for (const auto& [command, source] : queued_) {
      queued += "; queued: " + DescribeGaitCommand(command);
    }
    return fmt::format("gait {} (waiting for the first state{})", initial_.name,
                       queued);
  }
  const GaitController& c = *controller_;
  return fmt::format("motion {} {:.2f}, gait {} ({})", ToString(c.motion()),
                     c.strength(), c.active_gait().name,
                     ToString(c.active_kind()));
}

gait_status_t GaitNode::status() const {
  gait_status_t s{};
  s.utime = static_cast<int64_t>(std::llround(pacer_.last_time() * 1e6));
  s.seq = status_seq_;
  s.robot = options_.robot;
  s.sender = options_.sender;
  s.sim_time = pacer_.have_last() ? pacer_.last_time() : 0.0;
  s.running = controller_ != nullptr;
  const Gait& gait = controller_ ? controller_->active_gait() : initial_;
  s.gait = gait.name;
  s.kind = ToString(gait.kind);
  WriteGaitParameters(gait.parameters, s.parameters);
  s.motion = ToString(controller_ ? controller_->motion() : Motion::kForward);
  s.strength = controller_ ? controller_->strength() : 1.0;
  s.stopped = controller_ && controller_->stopped();
  s.states_answered = counters_.states_answered;
  s.commands_applied = counters_.commands_applied;
  s.commands_rejected = counters_.commands_rejected;
  s.messages_malformed = counters_.messages_malformed;
  s.command_seq = ack_seq_;
  s.command_sender = ack_sender_;
  s.command_result = ack_result_;
  s.command_error = ack_error_;
  s.warning = warning_;
  for (const auto& [command, source] : queued_) {
    s.queued += (s.queued.empty() ? "" : "; ") + DescribeGaitCommand(command);
  }
  return s;
}

void GaitNode::PublishStatus(WallTime now, GaitOutbox* out) {
  out->Add(GaitStatusChannel(options_.prefix, options_.robot), status());
  ++status_seq_;
  last_status_ = now;
}

void GaitNode::Start(WallTime now, GaitOutbox* out) { PublishStatus(now, out); }

WallTime GaitNode::Tick(WallTime now, GaitOutbox* out) {
  std::vector<std::string> lines;
  watch_.Tick(now, &lines);
  for (std::string& line : lines) Log(std::move(line));
  WallTime due = AfterSeconds(last_status_, kHeartbeatInterval);
  if (now >= due) {
    PublishStatus(now, out);
    due = AfterSeconds(now, kHeartbeatInterval);
  }
  return due;
}

void GaitNode::Acknowledge(const gait_command_t& command, int8_t result,
                           const std::string& error) {
  ack_seq_ = command.seq;
  ack_sender_ = command.sender;
  ack_result_ = result;
  ack_error_ = error;
}

void GaitNode::CheckFit() {
  const std::string warning =
      MotionFitWarning(controller_->motion(), controller_->joint_axes());
  if (warning != warning_ && !warning.empty()) {
    Log("warning: robot " + options_.robot + ": " + warning);
  }
  warning_ = warning;
}

void GaitNode::Apply(const gait_command_t& command, const std::string& source,
                     WallTime now, GaitOutbox* out) {
  try {
    if (!controller_) {
      if (queued_.size() >= kMaxQueued) {
        ++counters_.commands_rejected;
        Acknowledge(command, gait_status_t::REJECTED,
                    "too many commands before the first state");
        Log(fmt::format(
            "rejected gait command from {}: too many before the first state",
            source));
      } else {
        queued_.emplace_back(command, source);
        Acknowledge(command, gait_status_t::QUEUED, "");
        Log(fmt::format("{}: {} queued (applies with the first state)", source,
                        DescribeGaitCommand(command)));
      }
      PublishStatus(now, out);
      return;
    }
    const std::string what = ApplyGaitCommand(command, controller_.get());
    ++counters_.commands_applied;
    Acknowledge(command, gait_status_t::APPLIED, "");
    Log(fmt::format("{}: {} -> {}", source, what, Describe()));
    CheckFit();
  } catch (const std::exception& e) {
    ++counters_.commands_rejected;
    Acknowledge(command, gait_status_t::REJECTED, e.what());
    Log(fmt::format("rejected gait command from {}: {} (keeping {})", source,
                    e.what(), Describe()));
  }
  PublishStatus(now, out);
}

void GaitNode::OnGaitCommand(const gait_command_t& command, WallTime now,
                             GaitOutbox* out) {
  if (!command.robot.empty() && command.robot != options_.robot) {
    ++counters_.commands_rejected;
    const std::string error =
        fmt::format("gait command for robot '{}' (this is {})", command.robot,
                    options_.robot);
    Acknowledge(command, gait_status_t::REJECTED, error);
    Log("rejected " + error);
    PublishStatus(now, out);
    return;
  }
  Apply(command, command.sender.empty() ? "lcm" : command.sender, now, out);
}

void GaitNode::OnMalformedState() { ++counters_.messages_malformed; }

void GaitNode::OnMalformedGait(WallTime now, GaitOutbox* out) {
  ++counters_.messages_malformed;
  ++counters_.commands_rejected;
  Log("rejected a gait command that does not decode as gait_command_t");
  PublishStatus(now, out);
}

void GaitNode::OnState(const robot_state_t& state, WallTime now,
                       GaitOutbox* out) {
  watch_.Heard(now);
  const bool had_controller = controller_ != nullptr;
  try {
    HandleState(state, out);
  } catch (const std::exception& e) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} not answered: {}", state.seq, e.what()));
  }
  if (!had_controller && controller_) {
    // The controller exists now: apply what waited for it, report once.
    while (!queued_.empty()) {
      auto [command, source] = queued_.front();
      queued_.pop_front();
      Apply(command, source, now, out);
    }
    PublishStatus(now, out);
  }
}

void GaitNode::HandleState(const robot_state_t& state, GaitOutbox* out) {
  if (!error_.empty()) return;
  if (state.robot != options_.robot) {
    ++counters_.states_foreign;
    return;
  }
  // Beyond kMaxSimTime (decades) the gait's phase would overflow to inf and
  // poison every later target: such a time is forged, not simulated.
  if (!std::isfinite(state.sim_time) || state.sim_time < 0 ||
      state.sim_time > kMaxSimTime) {
    ++counters_.messages_malformed;
    return;
  }
  if (!controller_) {
    std::vector<Axis> axes;
    try {
      axes = axes_for_(state.num_joints);
      if (static_cast<int>(axes.size()) != state.num_joints) {
        throw std::invalid_argument(
            fmt::format("the joint axes list {} joints but robot {} has {}",
                        axes.size(), options_.robot, state.num_joints));
      }
      controller_ = std::make_unique<GaitController>(axes, options_.controller);
      controller_->SetGait(initial_);
    } catch (const std::exception& e) {
      controller_.reset();
      error_ = e.what();
      return;
    }
    Log(fmt::format("robot {}: {} joints; {}", options_.robot, state.num_joints,
                    Describe()));
    if (!resume_path_.empty()) {
      const std::string path = resume_path_;
      resume_path_.clear();
      Restore(path);
    }
    CheckFit();
  }
  if (state.num_joints != controller_->joint_count()) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} has {} joints, expected {}", state.seq,
                    state.num_joints, controller_->joint_count()));
    return;
  }
  std::string note;
  const StatePacer::Decision decision =
      pacer_.Decide(state, watch_.may_be_lockstep(), &note);
  if (!note.empty()) Log(std::move(note));
  if (decision.verdict == StatePacer::Verdict::kRepeat) {
    // The simulator sent the state again (our answer may have been lost).
    ++counters_.states_repeated;
    out->Add(CommandChannel(options_.prefix, options_.robot), *decision.repeat);
    return;
  }
  if (decision.restarted) {
    Log(
        fmt::format("sim time went back to {} s (reset or checkpoint): the "
                    "gait starts again from rest",
                    state.sim_time));
    controller_->Reset();
  }
  if (decision.verdict == StatePacer::Verdict::kSkip) {
    ++counters_.states_skipped;
    return;
  }
  snapshots_.insert_or_assign(
      state.sim_time,
      Snapshot{*controller_, pacer_.have_last(), pacer_.last_time()});
  while (snapshots_.size() > kMaxSnapshots) {
    // Drop the oldest in sim time; after a reset that is the stale future.
    snapshots_.erase(snapshots_.begin());
  }
  const double dt =
      pacer_.have_last() ? state.sim_time - pacer_.last_time() : 0.0;
  FeedSensors(state);
  const std::vector<double>& targets = controller_->Update(dt);
  for (double t : targets) {
    if (!std::isfinite(t)) {
      // Never send a non-finite target; start the gait again from rest.
      ++counters_.messages_malformed;
      Log(
          fmt::format("state seq {} gave a non-finite target; the gait "
                      "starts again from rest",
                      state.seq));
      controller_->Reset();
      pacer_.Restart();
      return;
    }
  }

  out->Add(CommandChannel(options_.prefix, options_.robot),
           pacer_.Answer(state, targets));
  ++counters_.states_answered;
}

void GaitNode::OnSimControl(const sim_control_t& request) {
  if (request.command != sim_control_t::SAVE_CHECKPOINT &&
      request.command != sim_control_t::LOAD_CHECKPOINT) {
    return;
  }
  if (requests_.size() >= kMaxRequests) requests_.erase(requests_.begin());
  requests_[{request.sender, request.seq}] = request;
}

void GaitNode::OnSimStatus(const sim_status_t& status, WallTime now,
                           GaitOutbox* out) {
  std::vector<std::string> lines;
  watch_.OnStatus(status, now, &lines);
  for (std::string& line : lines) Log(std::move(line));
  if (!status.waiting_for.empty() && !warned_other_name_) {
    // A lockstep simulator waiting for controllers by name, and this one
    // is not among them: most often a --name that is not the one in the
    // simulator's --controllers (its answers are refused, and it only sees
    // the same state again, "repeated"). Say so, once.
    std::vector<std::string> names;
    std::stringstream list(status.waiting_for);
    for (std::string n; std::getline(list, n, ',');) names.push_back(n);
    if (std::find(names.begin(), names.end(), options_.sender) == names.end()) {
      warned_other_name_ = true;
      Log(fmt::format(
          "warning: the simulator is waiting for controller(s) '{}', not "
          "for this one ('{}'); if that name is meant to be this "
          "controller, start it with --name {}, or mrsim-sim with "
          "--controllers {}",
          status.waiting_for, options_.sender, names.front(), options_.sender));
    }
  }
  const auto it = requests_.find({status.control_sender, status.control_seq});
  if (it == requests_.end()) return;
  const sim_control_t request = it->second;
  requests_.erase(it);
  if (!status.control_ok) return;
  const std::string path = GaitCheckpointPath(request.path, options_.robot);
  try {
    if (request.command == sim_control_t::SAVE_CHECKPOINT) {
      WriteCheckpoint(path, status.sim_time);
      Log(fmt::format("saved the gait at sim time {:.3f} s to {}",
                      status.sim_time, path));
    } else if (controller_) {
      Restore(request.path);
      PublishStatus(now, out);
    } else {
      resume_path_ = request.path;
    }
  } catch (const std::exception& e) {
    Log(fmt::format("checkpoint: {}", e.what()));
  }
}

void GaitNode::Resume(const std::string& checkpoint) {
  const std::string path = GaitCheckpointPath(checkpoint, options_.robot);
  std::ifstream in(path);
  if (!in) {
    throw UsageError(
        "--resume: cannot read " + path +
        " (mrsim-gait writes it when the simulator saves that checkpoint on "
        "request, e.g. mrsim-ctl save; --checkpoint-on-exit saves the "
        "simulator only: start mrsim-gait without --resume and the gait "
        "starts from rest)");
  }
  resume_path_ = checkpoint;
}

void GaitNode::WriteCheckpoint(const std::string& path, double sim_time) const {
  const Snapshot* snap = nullptr;
  Snapshot current{controller_ ? *controller_ : GaitController({Axis::kPitch}),
                   pacer_.have_last(), pacer_.last_time()};
  const auto found = snapshots_.find(sim_time);
  if (found != snapshots_.end()) {
    snap = &found->second;
  } else if (controller_ &&
             (!pacer_.have_last() || pacer_.last_time() < sim_time)) {
    snap = &current;  // the saved state is not answered yet: now is right
  }
  if (snap == nullptr) {
    throw std::runtime_error(fmt::format(
        "no gait state at sim time {} s (states skipped or too old); {} not "
        "written",
        sim_time, path));
  }
  std::ostringstream text;
  text << kCheckpointTag << "\n"
       << "robot " << options_.robot << "\n"
       << "sim_time " << ExactNumber(sim_time) << "\n"
       << "have_last " << (snap->have_last ? 1 : 0) << "\n"
       << "last_time " << ExactNumber(snap->last_time) << "\n"
       << snap->controller.SaveState() << "\n";
  WriteFileAtomically(path, text.str());
}

void GaitNode::Restore(const std::string& checkpoint) {
  const std::string path = GaitCheckpointPath(checkpoint, options_.robot);
  std::ifstream in(path);
  std::string tag, key, robot, state;
  std::string time_text, last_text;
  int have_last = 0;
  if (!(in >> tag) || tag != kCheckpointTag) {
    throw std::runtime_error(path + ": not a mrsim-gait checkpoint");
  }
  if (!(in >> key >> robot) || key != "robot" || robot != options_.robot) {
    throw std::runtime_error(path + ": not robot " + options_.robot + "'s");
  }
  if (!(in >> key >> time_text) || key != "sim_time" ||
      !(in >> key >> have_last) || key != "have_last" ||
      !(in >> key >> last_text) || key != "last_time") {
    throw std::runtime_error(path + ": bad header");
  }
  in >> std::ws;
  std::getline(in, state);
  GaitController restored = *controller_;
  try {
    restored.LoadState(state);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  // The whole text: a damaged file must not restore 0 in silence.
  const auto time_of = [&](const std::string& text, const char* key) {
    const std::optional<double> t = ParseWholeNumber(text);
    if (!t || !std::isfinite(*t)) {
      throw std::runtime_error(path + ": " + key + ": expected a time, got '" +
                               text + "'");
    }
    return *t;
  };
  const double saved_time = time_of(time_text, "sim_time");
  const double last_time = time_of(last_text, "last_time");
  *controller_ = std::move(restored);
  pacer_.Restore(have_last != 0, last_time);
  snapshots_.clear();
  Log(fmt::format("restored the gait saved at sim time {:.3f} s from {}",
                  saved_time, path));
}

std::string GaitNode::Summary() const {
  const GaitNodeCounters& n = counters_;
  return fmt::format(
      "{}: answered {} states ({} repeated, {} skipped), gait commands "
      "applied {}, rejected {}, malformed messages {}",
      options_.robot, n.states_answered, n.states_repeated, n.states_skipped,
      n.commands_applied, n.commands_rejected, n.messages_malformed);
}

}  // namespace mrsim
