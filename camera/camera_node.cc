#include "camera/camera_node.h"

#include <cmath>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "common/printable.h"
#include "sim_core/codec/state_message.h"

namespace mrsim {
namespace {

constexpr size_t kMaxLogLines = 1000;
// Scene states kept for the periods still to complete (one or two in
// practice; a few more for a burst).
constexpr size_t kKeptScenes = 8;
// Sim times this close below a frame's time still take it: k / rate is
// rarely exactly representable.
constexpr double kSlotTolerance = 1e-9;

std::int64_t SlotOf(double sim_time, double rate) {
  return static_cast<std::int64_t>(
      std::floor(sim_time * rate + kSlotTolerance));
}

}  // namespace

CameraNode::CameraNode(CameraNodeOptions options, CameraFrameRenderer* renderer,
                       WallTime now)
    : options_(std::move(options)),
      renderer_(renderer),
      watch_(StateChannel(options_.prefix, "<robot>") + " or " +
                 SimStatusChannel(options_.prefix),
             options_.exit_with_sim, now) {
  if (renderer_ == nullptr) throw std::invalid_argument("camera: no renderer");
  if (options_.jpeg_quality < 0 || options_.jpeg_quality > 100) {
    throw std::invalid_argument("--jpeg-quality " +
                                std::to_string(options_.jpeg_quality) +
                                " (expected 1..100)");
  }
  const std::vector<std::string>& robots = renderer_->robots();
  const std::vector<ScenarioCamera>& cameras = renderer_->cameras();
  // --robot names a robot, or the owner of cameras on no robot ("loose",
  // "scene").
  bool found = options_.robot.empty();
  for (size_t r = 0; r < robots.size(); ++r) {
    channels_[StateChannel(options_.prefix, robots[r])] = static_cast<int>(r);
    found = found || robots[r] == options_.robot;
  }
  for (const ScenarioCamera& c : cameras) {
    found = found || c.owner == options_.robot;
  }
  if (!found) {
    std::string names;
    for (const std::string& r : robots)
      names += (names.empty() ? "" : ", ") + r;
    throw std::invalid_argument("--robot '" + options_.robot +
                                "' is not a robot of the scenario (it has " +
                                names +
                                ") nor the owner of its cameras on no "
                                "robot ('loose', 'scene')");
  }
  robot_imaged_.assign(robots.size(), false);
  bool world = false;  // a camera on no robot is pictured
  for (size_t i = 0; i < cameras.size(); ++i) {
    if (!options_.robot.empty() && cameras[i].owner != options_.robot) {
      continue;
    }
    imaged_.push_back(static_cast<int>(i));
    if (cameras[i].robot >= 0) {
      robot_imaged_.at(cameras[i].robot) = true;
    } else {
      world = true;
    }
  }
  // A camera on the world shows every robot, and any robot's controller
  // may wait for its pictures: in lockstep every robot is answered.
  if (world) robot_imaged_.assign(robots.size(), true);
  if (imaged_.empty()) {
    throw std::invalid_argument(
        options_.robot.empty()
            ? "the scenario has no camera (a <Camera> in a sensor module's "
              "or a scene object's <cameras>)"
            : "'" + options_.robot + "' has no camera");
  }
  if (renderer_->has_loose_parts()) {
    loose_channel_ = StateChannel(options_.prefix, kLooseOwnerName);
  }
  next_slot_.assign(imaged_.size(), 0);
  answers_.resize(robots.size());
  gathering_.states.resize(robots.size());
}

std::vector<std::string> CameraNode::StateChannels() const {
  std::vector<std::string> out;
  for (const auto& [channel, robot] : channels_) out.push_back(channel);
  if (!loose_channel_.empty()) out.push_back(loose_channel_);
  return out;
}

void CameraNode::Log(std::string line) {
  if (log_.size() < kMaxLogLines) log_.push_back(std::move(line));
}

std::vector<std::string> CameraNode::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

void CameraNode::Malformed(std::string what) {
  ++counters_.malformed;
  last_error_ = Printable(what);
}

void CameraNode::OnMalformed(const std::string& what) { Malformed(what); }

void CameraNode::OnSimStatus(const sim_status_t& status, WallTime now) {
  std::vector<std::string> lines;
  watch_.OnStatus(status, now, &lines);
  for (std::string& line : lines) Log(std::move(line));
}

WallTime CameraNode::Tick(WallTime now) {
  std::vector<std::string> lines;
  watch_.Tick(now, &lines);
  for (std::string& line : lines) Log(std::move(line));
  return AfterSeconds(now, 0.5);
}

void CameraNode::OnScene(const scene_state_t& scene, WallTime now) {
  watch_.Heard(now);
  if (scene.seq < 0 || scene.utime < 0 || !std::isfinite(scene.sim_time)) {
    Malformed("scene state with a negative seq or time");
    return;
  }
  std::vector<SceneObjectState> objects;
  try {
    objects = FromSceneStateMessage(scene);
  } catch (const std::exception& e) {
    Malformed(std::string("scene state: ") + e.what());
    return;
  }
  const std::string problem = renderer_->CheckScene(objects);
  if (!problem.empty()) {
    Malformed("scene state: " + problem);
    return;
  }
  if (scene.seq <= done_seq_) return;  // a re-send of a scene already used
  scenes_[scene.seq] = std::move(objects);
  while (scenes_.size() > kKeptScenes) scenes_.erase(scenes_.begin());
}

void CameraNode::OnLoose(const robot_state_t& msg, WallTime now) {
  watch_.Heard(now);
  if (msg.robot != kLooseOwnerName) {
    Malformed(loose_channel_ + ": state of robot '" + msg.robot + "'");
    return;
  }
  if (msg.seq < 0 || msg.utime < 0 || !(msg.sim_time >= 0) ||
      msg.sim_time > kMaxSimTime) {
    Malformed(loose_channel_ +
              ": negative seq or time, or a time beyond 1e9 s");
    return;
  }
  RobotState state;
  try {
    state = FromRobotStateMessage(msg);
  } catch (const std::exception& e) {
    Malformed(loose_channel_ + ": " + e.what());
    return;
  }
  const std::string problem = renderer_->CheckLoose(state);
  if (!problem.empty()) {
    Malformed(loose_channel_ + ": " + problem);
    return;
  }
  if (msg.seq <= done_seq_) return;  // a re-send of a state already used
  looses_[msg.seq] = std::move(state);
  while (looses_.size() > kKeptScenes) looses_.erase(looses_.begin());
}

void CameraNode::OnState(const std::string& channel, const robot_state_t& msg,
                         WallTime now, CameraOutbox* out) {
  if (!loose_channel_.empty() && channel == loose_channel_) {
    OnLoose(msg, now);
    return;
  }
  watch_.Heard(now);
  const auto it = channels_.find(channel);
  if (it == channels_.end()) {
    Malformed(channel + ": not a state channel of the scenario");
    return;
  }
  const int robot = it->second;
  if (msg.robot != renderer_->robots()[robot]) {
    Malformed(channel + ": state of robot '" + msg.robot + "'");
    return;
  }
  if (msg.seq < 0 || msg.utime < 0 || !(msg.sim_time >= 0) ||
      msg.sim_time > kMaxSimTime) {
    Malformed(channel + ": negative seq or time, or a time beyond 1e9 s");
    return;
  }
  RobotState state;
  try {
    state = FromRobotStateMessage(msg);
  } catch (const std::exception& e) {
    Malformed(channel + ": " + e.what());
    return;
  }
  const std::string problem = renderer_->Check(robot, state);
  if (!problem.empty()) {
    Malformed(channel + ": " + problem);
    return;
  }
  if (msg.seq <= done_seq_) {
    // Lockstep re-sends the states it still waits for: answer again (the
    // same answer, which the simulator takes as a repeat).
    ++counters_.stale;
    if (options_.clock == ClockMode::kLockstep && msg.seq == done_seq_ &&
        answers_[robot]) {
      out->Add(CommandChannel(options_.prefix, msg.robot), *answers_[robot]);
      ++counters_.answers;
    }
    return;
  }
  if (msg.seq < gathering_.seq) {
    ++counters_.stale;
    return;
  }
  if (msg.seq > gathering_.seq) {
    // A new period; one left incomplete (a state lost) is given up.
    gathering_.seq = msg.seq;
    gathering_.sim_time = msg.sim_time;
    gathering_.utime = msg.utime;
    gathering_.count = 0;
    for (auto& s : gathering_.states) s.reset();
  }
  if (gathering_.states[robot]) {
    ++counters_.stale;  // a second state of this robot for the same seq
    return;
  }
  gathering_.states[robot] = std::move(state);
  ++gathering_.count;
  ++counters_.states;
  if (!gathering_.complete()) return;

  done_seq_ = gathering_.seq;
  if (options_.clock == ClockMode::kLockstep) {
    Picture(gathering_, out);
    Answer(gathering_, out);
  } else {
    pending_ = gathering_;
  }
  gathering_.seq = -1;
  gathering_.count = 0;
  for (auto& s : gathering_.states) s.reset();
}

void CameraNode::Flush(CameraOutbox* out) {
  if (!pending_) return;
  Picture(*pending_, out);
  pending_.reset();
}

void CameraNode::Picture(const Period& period, CameraOutbox* out) {
  const std::vector<ScenarioCamera>& cameras = renderer_->cameras();
  if (last_time_ < 0 || period.sim_time < last_time_) {
    // The first period heard (a camera started after the simulator has
    // missed nothing it could have pictured), or a reset or a checkpoint
    // load took the time back: the frames start there.
    for (size_t k = 0; k < imaged_.size(); ++k) {
      next_slot_[k] = SlotOf(period.sim_time, cameras[imaged_[k]].part.rate);
    }
  }
  last_time_ = period.sim_time;
  std::vector<const RobotState*> states;
  for (const auto& s : period.states) states.push_back(s ? &*s : nullptr);
  const std::vector<SceneObjectState>* scene = nullptr;
  auto newest = scenes_.upper_bound(period.seq);
  if (newest != scenes_.begin()) scene = &std::prev(newest)->second;
  const RobotState* loose = nullptr;
  auto newest_loose = looses_.upper_bound(period.seq);
  if (newest_loose != looses_.begin()) {
    loose = &std::prev(newest_loose)->second;
  }

  for (size_t k = 0; k < imaged_.size(); ++k) {
    const ScenarioCamera& camera = cameras[imaged_[k]];
    const std::int64_t slot = SlotOf(period.sim_time, camera.part.rate);
    if (slot < next_slot_[k]) continue;  // not due
    counters_.dropped += slot - next_slot_[k];
    next_slot_[k] = slot + 1;
    renderer_->Render(imaged_[k], states, scene, loose, period.seq, &picture_);
    CameraImageHeader header;
    header.robot = camera.owner;
    header.sender = options_.sender;
    header.camera = camera.camera;
    header.sensor_module = camera.sensor_module;
    header.name = camera.name;
    header.seq = period.seq;
    header.sim_time = period.sim_time;
    camera_image_t msg =
        EncodeCameraImage(header, picture_, options_.jpeg_quality);
    out->Add(CameraChannel(options_.prefix, camera.owner), std::move(msg));
    ++counters_.pictures;
  }
  // Scenes older than this period will never be shown again.
  scenes_.erase(scenes_.begin(), scenes_.lower_bound(period.seq));
  looses_.erase(looses_.begin(), looses_.lower_bound(period.seq));
}

void CameraNode::Answer(const Period& period, CameraOutbox* out) {
  const std::vector<std::string>& robots = renderer_->robots();
  for (size_t r = 0; r < robots.size(); ++r) {
    answers_[r].reset();
    if (!robot_imaged_[r]) continue;
    joint_command_t cmd{};
    cmd.utime = period.utime;
    cmd.seq = ++answer_seq_;
    cmd.robot = robots[r];
    cmd.sender = options_.sender;
    cmd.state_seq = period.seq;
    cmd.num_joints = 0;
    answers_[r] = cmd;
    out->Add(CommandChannel(options_.prefix, robots[r]), std::move(cmd));
    ++counters_.answers;
  }
}

std::string CameraNode::Summary() const {
  const CameraNodeCounters& c = counters_;
  std::ostringstream line;
  line << "pictures published " << c.pictures << ", dropped " << c.dropped
       << ", malformed " << c.malformed << " (states taken " << c.states
       << ", stale " << c.stale;
  if (options_.clock == ClockMode::kLockstep) {
    line << ", answers " << c.answers;
  }
  line << ")";
  if (c.malformed > 0 && !last_error_.empty()) {
    line << "; last malformed: " << last_error_;
  }
  return line.str();
}

}  // namespace mrsim
