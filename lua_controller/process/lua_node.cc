#include "lua_controller/process/lua_node.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "camera/camera_image_codec.h"
#include "lcmtypes/runtime/channels.h"
#include "lua_controller/grey_thumbnail.h"
#include "lua_controller/lua_robot_state_fill.h"
#include "sim_core/codec/state_message.h"

namespace mrsim {
namespace {

constexpr size_t kMaxLogLines = 1000;

}  // namespace

LuaNode::LuaNode(LuaNodeOptions options, std::unique_ptr<LuaScript> script,
                 std::function<std::vector<Axis>(int)> axes_for, WallTime now)
    : options_(std::move(options)),
      script_(std::move(script)),
      axes_for_(std::move(axes_for)),
      pacer_(options_.robot, options_.sender, options_.rate),
      watch_(
          fmt::format("{} or {}", StateChannel(options_.prefix, options_.robot),
                      SimStatusChannel(options_.prefix)),
          options_.exit_with_sim, now) {
  if (!script_) throw std::invalid_argument("LuaNode: no script");
}

void LuaNode::Log(std::string line) {
  if (log_.size() < kMaxLogLines) log_.push_back(std::move(line));
}

std::vector<std::string> LuaNode::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

WallTime LuaNode::Tick(WallTime now, LuaOutbox* out) {
  std::vector<std::string> lines;
  watch_.Tick(now, &lines);
  for (std::string& line : lines) Log(std::move(line));
  if (takes_gait_commands() && error_.empty() && now >= next_heartbeat_) {
    PublishStatus(now, out);
  }
  ReleaseWaiting(now, out);
  WallTime next = AfterSeconds(now, 0.5);
  if (takes_gait_commands()) next = std::min(next, next_heartbeat_);
  if (!waiting_.empty()) {
    // Soon: a status saying the clock is not lockstep releases them too.
    next = std::min({next, AfterSeconds(now, 0.05),
                     AfterSeconds(waiting_.front().since, kCameraWait)});
  }
  return next;
}

bool LuaNode::WaitsForCamera(int64_t seq) const {
  return options_.cameras != 0 && watch_.may_be_lockstep() && !camera_silent_ &&
         (options_.cameras > 0 || camera_heard_) && seq > camera_answered_ &&
         seq > last_processed_seq_;
}

void LuaNode::ReleaseWaiting(WallTime now, LuaOutbox* out, bool make_room) {
  while (!waiting_.empty() && error_.empty()) {
    const Waiting& w = waiting_.front();
    if (WaitsForCamera(w.state.seq)) {
      if (make_room) {
        make_room = false;
        Log(fmt::format(
            "state seq {} answered without waiting for {}'s pictures: {} "
            "states wait already",
            w.state.seq, options_.camera_sender, waiting_.size()));
      } else if (SecondsBetween(w.since, now) < kCameraWait) {
        break;
      } else {
        ++counters_.camera_timeouts;
        camera_silent_ = true;
        Log(fmt::format(
            "no answer from {} to state seq {} in {} s: answering without "
            "its pictures, and not waiting for them until it is heard "
            "again (this run may differ from a rerun)",
            options_.camera_sender, w.state.seq, kCameraWait));
      }
    }
    const robot_state_t state = std::move(waiting_.front().state);
    waiting_.pop_front();
    Process(state, out);
    make_room = false;
  }
}

void LuaNode::OnCameraImage(const camera_image_t& image, WallTime now,
                            LuaOutbox* out) {
  if (options_.cameras == 0 || image.robot != options_.robot) return;
  if (image.camera < 0 || image.camera >= kMaxCameras ||
      !std::isfinite(image.sim_time)) {
    ++counters_.pictures_malformed;
    return;
  }
  CameraPicture picture;
  try {
    picture = DecodeCameraImage(image);
  } catch (const std::invalid_argument& e) {
    if (counters_.pictures_malformed++ == 0) {
      Log(fmt::format("a picture of camera {} dropped: {}", image.camera,
                      e.what()));
    }
    return;
  }
  const GreyThumbnail thumb =
      MakeGreyThumbnail(picture.width, picture.height, picture.rgb.data());
  LuaRobotState::Camera c;
  c.width = picture.width;
  c.height = picture.height;
  c.seq = image.seq;
  c.sim_time = image.sim_time;
  c.grey_width = thumb.width;
  c.grey_height = thumb.height;
  c.grey = thumb.grey;
  if (pictures_.size() <= static_cast<size_t>(image.camera)) {
    pictures_.resize(static_cast<size_t>(image.camera) + 1);
  }
  auto& kept = pictures_[static_cast<size_t>(image.camera)];
  kept.push_back(std::move(c));
  if (kept.size() > kPicturesKept) kept.pop_front();
  ++counters_.pictures_received;
  camera_heard_ = true;
  camera_silent_ = false;
  ReleaseWaiting(now, out);
}

void LuaNode::OnCommand(const joint_command_t& command, WallTime now,
                        LuaOutbox* out) {
  if (command.sender != options_.camera_sender ||
      command.robot != options_.robot) {
    return;
  }
  camera_answered_ = std::max(camera_answered_, command.state_seq);
  camera_heard_ = true;
  camera_silent_ = false;
  ReleaseWaiting(now, out);
}

// The newest picture of each camera that shows this state or an earlier
// one: in lockstep all of them have come (the camera process answered the
// state after sending them), so every run picks the same.
void LuaNode::FillCameras(int64_t seq) {
  const size_t n =
      std::max(options_.cameras > 0 ? static_cast<size_t>(options_.cameras) : 0,
               pictures_.size());
  input_.cameras.assign(n, LuaRobotState::Camera{});
  for (size_t k = 0; k < pictures_.size(); ++k) {
    const LuaRobotState::Camera* best = nullptr;
    for (const LuaRobotState::Camera& c : pictures_[k]) {
      if (c.seq <= seq && (best == nullptr || c.seq >= best->seq)) best = &c;
    }
    if (best != nullptr) input_.cameras[k] = *best;
  }
}

void LuaNode::PublishStatus(WallTime now, LuaOutbox* out) {
  status_.seq += 1;
  status_.robot = options_.robot;
  status_.sender = options_.sender;
  status_.kind = "lua";
  status_.gait = script_->name();
  status_.states_answered = counters_.states_answered;
  status_.commands_applied = counters_.commands_applied;
  status_.commands_rejected = counters_.commands_rejected;
  status_.messages_malformed = counters_.messages_malformed;
  out->Add(GaitStatusChannel(options_.prefix, options_.robot), status_);
  next_heartbeat_ = AfterSeconds(now, kHeartbeatInterval);
}

void LuaNode::OnGaitCommand(const gait_command_t& c, WallTime now,
                            LuaOutbox* out) {
  if (!takes_gait_commands() || !error_.empty()) return;
  LuaGaitCommand command;
  command.sender = c.sender;
  std::string refusal;
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!c.robot.empty() && c.robot != options_.robot) {
    refusal = fmt::format("a command for robot '{}' (this is '{}')", c.robot,
                          options_.robot);
  } else if (!finite(c.strength) || c.strength < -1 || c.strength > 1) {
    refusal = fmt::format("strength {} (expected -1 to 1)", c.strength);
  } else if (c.has_direction &&
             !(finite(c.forward) && finite(c.turn) && c.forward >= -1 &&
               c.forward <= 1 && c.turn >= -1 && c.turn <= 1)) {
    refusal = "direction out of range (forward and turn are -1 to 1)";
  } else if (c.has_parameters && !std::all_of(std::begin(c.parameters),
                                              std::end(c.parameters), finite)) {
    refusal = "a gait parameter is not a finite number";
  } else {
    command.motion = c.motion;
    command.strength = c.strength;
    command.gait = c.gait;
    if (c.has_parameters) {
      command.parameters.assign(std::begin(c.parameters),
                                std::end(c.parameters));
    }
    command.has_direction = c.has_direction;
    command.forward = c.forward;
    command.turn = c.turn;
    try {
      refusal = script_->OnGaitCommand(command);
    } catch (const LuaScriptError& e) {
      error_ = e.what();
      return;
    }
    for (std::string& line : script_->TakePrinted()) {
      Log("print: " + std::move(line));
    }
  }
  status_.command_seq = c.seq;
  status_.command_sender = c.sender;
  status_.command_error = refusal;
  if (refusal.empty()) {
    ++counters_.commands_applied;
    status_.command_result = gait_status_t::APPLIED;
    if (!c.motion.empty()) {
      status_.motion = c.motion;
      status_.strength = c.strength;
      status_.stopped = c.motion == "stop";
    }
  } else {
    ++counters_.commands_rejected;
    status_.command_result = gait_status_t::REJECTED;
    Log(fmt::format("gait command {} from {} refused: {}", c.seq, c.sender,
                    refusal));
  }
  PublishStatus(now, out);
}

void LuaNode::OnSimStatus(const sim_status_t& status, WallTime now) {
  std::vector<std::string> lines;
  watch_.OnStatus(status, now, &lines);
  for (std::string& line : lines) Log(std::move(line));
}

void LuaNode::OnState(const robot_state_t& state, WallTime now,
                      LuaOutbox* out) {
  watch_.Heard(now);
  if (!error_.empty()) return;
  if (state.robot == options_.robot &&
      (WaitsForCamera(state.seq) ||
       (!waiting_.empty() && state.seq > last_processed_seq_))) {
    for (const Waiting& w : waiting_) {
      if (w.state.seq == state.seq) return;  // sent again while it waits
    }
    if (waiting_.size() >= kMaxWaiting) ReleaseWaiting(now, out, true);
    waiting_.push_back({state, now});
    ++counters_.states_waited;
    ReleaseWaiting(now, out);  // in order, behind states that wait
    return;
  }
  Process(state, out);
}

void LuaNode::Process(const robot_state_t& state, LuaOutbox* out) {
  if (state.robot == options_.robot) {
    last_processed_seq_ = std::max(last_processed_seq_, state.seq);
  }
  try {
    HandleState(state, out);
  } catch (const LuaScriptError& e) {
    error_ = e.what();
  } catch (const std::exception& e) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} not answered: {}", state.seq, e.what()));
  }
  for (std::string& line : script_->TakePrinted()) {
    Log("print: " + std::move(line));
  }
}

void LuaNode::HandleState(const robot_state_t& state, LuaOutbox* out) {
  if (state.robot != options_.robot) {
    ++counters_.states_foreign;
    return;
  }
  if (!std::isfinite(state.sim_time) || state.sim_time < 0 ||
      state.sim_time > kMaxSimTime || state.num_joints < 0 ||
      static_cast<size_t>(state.num_joints) != state.joints.size()) {
    ++counters_.messages_malformed;
    return;
  }
  if (!axes_) {
    std::vector<Axis> axes;
    try {
      axes = axes_for_(state.num_joints);
      if (static_cast<int>(axes.size()) != state.num_joints) {
        throw std::invalid_argument(
            fmt::format("the joint axes list {} joints but robot {} has {}",
                        axes.size(), options_.robot, state.num_joints));
      }
    } catch (const std::invalid_argument& e) {
      error_ = e.what();
      return;
    }
    axes_.emplace();
    for (Axis a : axes) axes_->push_back(a == Axis::kYaw ? "yaw" : "pitch");
    Log(fmt::format("robot {}: {} joints; running {}", options_.robot,
                    state.num_joints, script_->name()));
  }
  if (static_cast<size_t>(state.num_joints) != axes_->size()) {
    ++counters_.messages_malformed;
    Log(fmt::format("state seq {} has {} joints, expected {}", state.seq,
                    state.num_joints, axes_->size()));
    return;
  }
  std::string note;
  const StatePacer::Decision decision =
      pacer_.Decide(state, watch_.may_be_lockstep(), &note);
  if (!note.empty()) Log(std::move(note));
  // A reset or a loaded checkpoint (decision.restarted): the script's t
  // starts again with the state's sim time.
  if (decision.verdict == StatePacer::Verdict::kRepeat) {
    ++counters_.states_repeated;
    out->Add(CommandChannel(options_.prefix, options_.robot), *decision.repeat);
    return;
  }
  if (decision.verdict == StatePacer::Verdict::kSkip) {
    ++counters_.states_skipped;
    return;
  }
  // The same conversion as the optimiser's Lua episodes make from the
  // physics (lua_robot_state_fill.h).
  FillLuaRobotState(FromRobotStateMessage(state), &input_);
  input_.axes = *axes_;
  FillCameras(state.seq);
  std::vector<double> targets = script_->Step(state.sim_time, input_);

  out->Add(CommandChannel(options_.prefix, options_.robot),
           pacer_.Answer(state, std::move(targets)));
  ++counters_.states_answered;
  status_.utime = state.utime;
  status_.sim_time = state.sim_time;
  if (!status_.running && takes_gait_commands()) {
    status_.running = true;  // said at once, as mrsim-gait does
    next_heartbeat_ = WallTime{};
  }
}

std::string LuaNode::Summary() const {
  const LuaNodeCounters& n = counters_;
  return fmt::format(
             "{}: answered {} states ({} repeated, {} skipped), malformed "
             "messages "
             "{}",
             options_.robot, n.states_answered, n.states_repeated,
             n.states_skipped, n.messages_malformed) +
         (options_.cameras != 0 &&
                  n.pictures_received + n.pictures_malformed > 0
              ? fmt::format(
                    ", pictures {} ({} malformed), states waited for {} {} "
                    "({} timed out)",
                    n.pictures_received, n.pictures_malformed,
                    options_.camera_sender, n.states_waited, n.camera_timeouts)
              : "");
}

}  // namespace mrsim
