#include "studio/live/live_session.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "gait_controller/motion.h"
#include "gait_controller/process/gait_parameters_message.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "logger/generic_flattener.h"
#include "logger/robot_state_flattener.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim::studio {
namespace {

// The requests kept for the window's list; older ones are forgotten.
constexpr size_t kMaxRequests = 200;
// Channels read (and so robots shown): a flood of new channel names is
// dropped and counted rather than growing the session without bound.
constexpr size_t kMaxChannels = 1000;

int64_t Fingerprint(const uint8_t* data, size_t size) {
  if (size < 8) return 0;
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | data[i];
  return static_cast<int64_t>(v);
}

bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.size() > prefix.size() && s.compare(0, prefix.size(), prefix) == 0;
}

// The cells of one CSV row (a quoted cell keeps its quotes: it is text,
// never a number).
void SplitCells(const std::string& row, std::vector<std::string_view>* cells) {
  cells->clear();
  size_t start = 0;
  bool quoted = false;
  for (size_t i = 0; i <= row.size(); ++i) {
    if (i < row.size() && row[i] == '"') quoted = !quoted;
    if (i == row.size() || (row[i] == ',' && !quoted)) {
      cells->emplace_back(row.data() + start, i - start);
      start = i + 1;
    }
  }
}

std::optional<double> ParseNumber(std::string_view cell) {
  double v = 0;
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  if (r.ec != std::errc() || r.ptr != cell.data() + cell.size()) {
    return std::nullopt;
  }
  return v;
}

template <class T>
bool Decode(const uint8_t* data, size_t size, T* msg) {
  return DecodeMessage(data, size, msg);
}

}  // namespace

// What the studio reads from one channel: its type, a flattener that names
// the columns as mrsim-log does, and the last row.
struct LiveSession::ChannelReader {
  int64_t hash = 0;
  std::string type_name;
  std::unique_ptr<MessageFlattener> flattener;
  FlatRow row;
  std::vector<std::string_view> cells;
  uint64_t shape_version = 0;
  std::map<std::string, size_t, std::less<>> index;  // column -> cell
};

LiveSession::LiveSession(LiveSessionOptions options)
    : options_(std::move(options)),
      registry_(LcmTypeRegistry::WithBuiltinTypes()) {}

LiveSession::~LiveSession() = default;

void LiveSession::Drop(const std::string& channel, const std::string& why,
                       bool foreign) {
  ++(foreign ? foreign_ : malformed_);
  last_error_ = channel + ": " + why;
}

LiveSession::ChannelReader* LiveSession::Reader(const std::string& channel,
                                                const uint8_t* data,
                                                size_t size) {
  const int64_t hash = Fingerprint(data, size);
  auto it = readers_.find(channel);
  if (it != readers_.end() && it->second->hash == hash) {
    return it->second.get();
  }
  if (it == readers_.end() && readers_.size() >= kMaxChannels) {
    Drop(channel, "more than " + std::to_string(kMaxChannels) + " channels",
         /*foreign=*/true);
    return nullptr;
  }
  const LcmStruct* type = size < 8 ? nullptr : registry_.FindByHash(hash);
  if (type == nullptr) {
    Drop(channel, "a message of no known type", /*foreign=*/size >= 8);
    return nullptr;
  }
  auto reader = std::make_unique<ChannelReader>();
  reader->hash = hash;
  reader->type_name = type->full_name();
  try {
    if (reader->type_name == "mrsim.robot_state_t") {
      reader->flattener = std::make_unique<RobotStateFlattener>(registry_);
    } else {
      reader->flattener = std::make_unique<GenericFlattener>(registry_, *type);
    }
  } catch (const std::exception& e) {
    Drop(channel, e.what(), /*foreign=*/true);
    return nullptr;
  }
  ChannelReader* raw = reader.get();
  readers_[channel] = std::move(reader);
  return raw;
}

void LiveSession::Feed(ChannelReader& reader, const std::string& channel,
                       const uint8_t* data, size_t size) {
  (void)data;
  (void)size;
  bool any = false;
  for (const auto& plot : plots_) any = any || plot->channel() == channel;
  if (!any) return;
  SplitCells(reader.row.values, &reader.cells);
  if (reader.shape_version != reader.flattener->shape_version() ||
      reader.index.empty()) {
    reader.shape_version = reader.flattener->shape_version();
    reader.index.clear();
    const auto& cols = reader.flattener->columns();
    for (size_t i = 0; i < cols.size(); ++i) reader.index.emplace(cols[i], i);
  }
  const auto time_cell = reader.index.find("time");
  if (time_cell == reader.index.end() ||
      time_cell->second >= reader.cells.size()) {
    return;  // a type without utime: nothing to plot against
  }
  const std::optional<double> t = ParseNumber(reader.cells[time_cell->second]);
  if (!t) return;
  for (const auto& plot : plots_) {
    if (plot->channel() != channel) continue;
    const auto col = reader.index.find(plot->column());
    if (col == reader.index.end() || col->second >= reader.cells.size()) {
      continue;  // not in this message's shape (a robot without that sensor)
    }
    if (const auto v = ParseNumber(reader.cells[col->second])) {
      plot->Add(*t, *v);
    }
  }
}

void LiveSession::OnMessage(const std::string& channel, const uint8_t* data,
                            size_t size, WallTime now) {
  const std::string prefix = options_.prefix + "_";
  if (!StartsWith(channel, prefix)) return;
  const std::string state_prefix = StateChannel(options_.prefix, "");
  const std::string gait_status_prefix = GaitStatusChannel(options_.prefix, "");
  const char* expected = nullptr;
  if (StartsWith(channel, state_prefix)) {
    expected = "mrsim.robot_state_t";
  } else if (StartsWith(channel, gait_status_prefix)) {
    expected = "mrsim.gait_status_t";
  } else if (channel == SceneChannel(options_.prefix)) {
    expected = "mrsim.scene_state_t";
  } else if (channel == SimStatusChannel(options_.prefix)) {
    expected = "mrsim.sim_status_t";
  }
  ++messages_;
  try {
    ChannelReader* reader = Reader(channel, data, size);
    if (reader == nullptr) return;
    if (expected != nullptr && reader->type_name != expected) {
      Drop(channel, reader->type_name + " where " + expected + " belongs",
           /*foreign=*/true);
      return;
    }
    // Checks the bytes (array lengths, strings) before any typed decode.
    if (!reader->flattener->Flatten(data, size, &reader->row)) {
      Drop(channel, "malformed " + reader->type_name, /*foreign=*/false);
      return;
    }
    if (expected == nullptr) {
      Feed(*reader, channel, data, size);
      return;
    }
    if (StartsWith(channel, state_prefix)) {
      const std::string name = channel.substr(state_prefix.size());
      robot_state_t msg;
      if (!Decode(data, size, &msg)) {
        Drop(channel, "malformed robot_state_t", false);
        return;
      }
      if (msg.robot != name) {
        Drop(channel, "the state of robot '" + msg.robot + "'", true);
        return;
      }
      if (name == kLooseOwnerName) {  // the loose parts: no robot to steer
        loose_ = std::move(msg);
        return;
      }
      LiveRobot& robot = robots_[name];
      if (robot.name.empty()) robot.first_heard = now;
      robot.name = name;
      robot.state = std::move(msg);
      ++robot.states;
      robot.last_heard = now;
      robot.silent = false;
    } else if (StartsWith(channel, gait_status_prefix)) {
      gait_status_t msg;
      if (!Decode(data, size, &msg)) {
        Drop(channel, "malformed gait_status_t", false);
        return;
      }
      OnGaitStatus(msg, now);
    } else if (channel == SceneChannel(options_.prefix)) {
      scene_state_t msg;
      if (!Decode(data, size, &msg)) {
        Drop(channel, "malformed scene_state_t", false);
        return;
      }
      scene_ = std::move(msg);
    } else {
      sim_status_t msg;
      if (!Decode(data, size, &msg)) {
        Drop(channel, "malformed sim_status_t", false);
        return;
      }
      OnSimStatus(msg);
    }
    Feed(*reader, channel, data, size);
  } catch (const std::exception& e) {
    // Out of memory for one message: counted, never thrown into LCM's C.
    Drop(channel, e.what(), false);
  }
}

void LiveSession::OnSimStatus(const sim_status_t& msg) {
  if (msg.control_sender == options_.sender) {
    for (LiveRequest& r : requests_) {
      if (r.kind != LiveRequest::Kind::kSim || r.seq != msg.control_seq ||
          r.state != LiveRequest::State::kPending) {
        continue;
      }
      r.state = msg.control_ok ? LiveRequest::State::kDone
                               : LiveRequest::State::kRefused;
      if (!msg.control_ok) r.error = msg.last_error;
    }
  }
  status_ = msg;
}

void LiveSession::OnGaitStatus(const gait_status_t& msg, WallTime now) {
  if (msg.command_sender == options_.sender) {
    for (LiveRequest& r : requests_) {
      if (r.kind != LiveRequest::Kind::kGait || r.seq != msg.command_seq ||
          r.state != LiveRequest::State::kPending) {
        continue;
      }
      if (msg.command_result == gait_status_t::REJECTED) {
        r.state = LiveRequest::State::kRefused;
        r.error = msg.command_error;
      } else if (msg.command_result == gait_status_t::APPLIED ||
                 msg.command_result == gait_status_t::QUEUED) {
        r.state = LiveRequest::State::kDone;
      }
    }
  }
  // A gait controller may speak before its robot's first state.
  LiveRobot& robot = robots_[msg.robot];
  if (robot.name.empty()) {
    robot.name = msg.robot;
    robot.first_heard = now;
    robot.last_heard = now;
  }
  robot.gait = msg;
  robot.gait_heard = now;
}

Steering LiveSession::SteeringOf(const std::string& name, WallTime now) const {
  using State = Steering::State;
  const LiveRobot* robot = this->robot(name);
  if (robot == nullptr) {
    return {State::kUnknown, fmt::format("robot '{}' not heard yet", name)};
  }
  if (robot->gait) {
    const double quiet = SecondsBetween(robot->gait_heard, now);
    if (quiet <= options_.request_timeout_s) return {State::kAnswered, ""};
    return {State::kUnanswered,
            fmt::format("the controller steering robot '{}' has not been "
                        "heard for {:.0f} s (it stopped?)",
                        name, quiet)};
  }
  if (SecondsBetween(robot->first_heard, now) < options_.gait_status_wait_s) {
    return {
        State::kUnknown,
        fmt::format("waiting to hear whether robot '{}' can be steered", name)};
  }
  return {State::kUnanswered,
          fmt::format("robot '{}' cannot be steered: its controller does not "
                      "take steering commands (only the gait controller "
                      "does; a Lua script or your own program drives it)",
                      name)};
}

void LiveSession::Tick(WallTime now) {
  for (LiveRequest& r : requests_) {
    if (r.state == LiveRequest::State::kPending &&
        SecondsBetween(r.sent, now) > options_.request_timeout_s) {
      r.state = LiveRequest::State::kNoAnswer;
      r.error =
          fmt::format("no answer within {:g} s", options_.request_timeout_s);
    }
  }
  for (auto& [name, robot] : robots_) {
    robot.silent =
        SecondsBetween(robot.last_heard, now) > options_.robot_silent_s;
  }
}

int64_t LiveSession::SendSim(sim_control_t msg, const std::string& what,
                             WallTime now, StudioOutbox* out) {
  LiveRequest r;
  r.kind = LiveRequest::Kind::kSim;
  r.seq = next_seq_++;
  r.what = what;
  r.sent = now;
  msg.seq = r.seq;
  msg.sender = options_.sender;
  msg.utime = 0;  // the simulator does not use it; no wall clock in the core
  out->Add(SimControlChannel(options_.prefix), std::move(msg));
  requests_.push_back(std::move(r));
  if (requests_.size() > kMaxRequests) requests_.erase(requests_.begin());
  return requests_.back().seq;
}

int64_t LiveSession::SendGait(gait_command_t msg, const std::string& what,
                              WallTime now, StudioOutbox* out) {
  // Sent to nobody it would only time out; say why at once instead.
  const Steering steering = SteeringOf(msg.robot, now);
  if (steering.state == Steering::State::kUnanswered) {
    throw std::runtime_error(steering.why);
  }
  LiveRequest r;
  r.kind = LiveRequest::Kind::kGait;
  r.seq = next_seq_++;
  r.what = what;
  r.sent = now;
  msg.seq = r.seq;
  msg.sender = options_.sender;
  msg.utime = 0;
  const std::string channel = GaitChannel(options_.prefix, msg.robot);
  out->Add(channel, std::move(msg));
  requests_.push_back(std::move(r));
  if (requests_.size() > kMaxRequests) requests_.erase(requests_.begin());
  return requests_.back().seq;
}

namespace {

sim_control_t Control(int8_t command) {
  sim_control_t msg{};
  msg.command = command;
  msg.speed = 1.0;
  return msg;
}

gait_command_t GaitCommand(const std::string& robot) {
  if (robot.empty()) throw std::invalid_argument("no robot to steer");
  gait_command_t msg{};
  msg.robot = robot;
  return msg;
}

}  // namespace

int64_t LiveSession::Pause(WallTime now, StudioOutbox* out) {
  return SendSim(Control(sim_control_t::PAUSE), "pause", now, out);
}

int64_t LiveSession::Resume(WallTime now, StudioOutbox* out) {
  return SendSim(Control(sim_control_t::RESUME), "resume", now, out);
}

int64_t LiveSession::Step(int periods, WallTime now, StudioOutbox* out) {
  if (periods < 1) {
    throw std::invalid_argument(
        fmt::format("step: {} periods (expected at least 1)", periods));
  }
  sim_control_t msg = Control(sim_control_t::STEP);
  msg.steps = periods;
  return SendSim(std::move(msg), fmt::format("step {}", periods), now, out);
}

int64_t LiveSession::Reset(WallTime now, StudioOutbox* out) {
  return SendSim(Control(sim_control_t::RESET), "reset", now, out);
}

int64_t LiveSession::SetSpeed(double speed, WallTime now, StudioOutbox* out) {
  if (!(speed > 0) || !std::isfinite(speed)) {
    throw std::invalid_argument(
        fmt::format("speed {} (expected a real-time factor above 0)", speed));
  }
  sim_control_t msg = Control(sim_control_t::SET_SPEED);
  msg.speed = speed;
  return SendSim(std::move(msg), fmt::format("speed {:g}", speed), now, out);
}

int64_t LiveSession::SaveCheckpoint(const std::string& path, WallTime now,
                                    StudioOutbox* out) {
  if (path.empty()) throw std::invalid_argument("save: no checkpoint path");
  sim_control_t msg = Control(sim_control_t::SAVE_CHECKPOINT);
  msg.path = path;
  return SendSim(std::move(msg), "save " + path, now, out);
}

int64_t LiveSession::SetLockAttached(const std::string& robot,
                                     const std::string& lock, bool attached,
                                     WallTime now, StudioOutbox* out) {
  if (robot.empty() || lock.empty()) {
    throw std::invalid_argument("lock: no robot or lock named");
  }
  sim_control_t msg =
      Control(attached ? sim_control_t::ATTACH : sim_control_t::DETACH);
  msg.robot = robot;
  msg.lock = lock;
  return SendSim(
      std::move(msg),
      fmt::format("{} {}/{}", attached ? "attach" : "detach", robot, lock), now,
      out);
}

int64_t LiveSession::LoadCheckpoint(const std::string& path, WallTime now,
                                    StudioOutbox* out) {
  if (path.empty()) throw std::invalid_argument("load: no checkpoint path");
  sim_control_t msg = Control(sim_control_t::LOAD_CHECKPOINT);
  msg.path = path;
  return SendSim(std::move(msg), "load " + path, now, out);
}

int64_t LiveSession::Steer(const std::string& robot, const std::string& motion,
                           double strength, WallTime now, StudioOutbox* out) {
  const std::optional<Motion> m = ParseMotion(motion);
  if (!m) {
    throw std::invalid_argument(
        "unknown motion '" + motion +
        "' (expected forward, backward, turn-left, turn-right, "
        "sidewind-left, sidewind-right, roll or stop)");
  }
  if (!(strength >= -1 && strength <= 1)) {
    throw std::invalid_argument(
        fmt::format("strength {} (expected -1 to 1)", strength));
  }
  gait_command_t msg = GaitCommand(robot);
  msg.motion = ToString(*m);
  msg.strength = strength;
  return SendGait(std::move(msg),
                  fmt::format("{} {} {:g}", robot, msg.motion, strength), now,
                  out);
}

int64_t LiveSession::SetGaitParameters(const std::string& robot,
                                       const std::vector<double>& parameters,
                                       WallTime now, StudioOutbox* out) {
  if (parameters.size() != GaitParameters::kVectorSize) {
    throw std::invalid_argument(fmt::format(
        "{} gait parameters (expected {}: {})", parameters.size(),
        GaitParameters::kVectorSize, fmt::join(GaitParameterNames(), ", ")));
  }
  for (size_t i = 0; i < parameters.size(); ++i) {
    if (!std::isfinite(parameters[i])) {
      throw std::invalid_argument(
          fmt::format("gait parameter {} is not a number", i));
    }
  }
  gait_command_t msg = GaitCommand(robot);
  msg.has_parameters = true;
  WriteGaitParameters(GaitParameters::FromVector(parameters), msg.parameters);
  return SendGait(std::move(msg), robot + " parameters", now, out);
}

int64_t LiveSession::SetGait(const std::string& robot, const std::string& gait,
                             WallTime now, StudioOutbox* out) {
  if (gait.empty()) throw std::invalid_argument("no gait name");
  gait_command_t msg = GaitCommand(robot);
  msg.gait = gait;
  return SendGait(std::move(msg), robot + " gait " + gait, now, out);
}

std::vector<const LiveRobot*> LiveSession::robots() const {
  std::vector<const LiveRobot*> all;
  for (const auto& [name, robot] : robots_) all.push_back(&robot);
  return all;
}

const LiveRobot* LiveSession::robot(const std::string& name) const {
  const auto it = robots_.find(name);
  return it == robots_.end() ? nullptr : &it->second;
}

const LiveRequest* LiveSession::request(int64_t seq) const {
  for (const LiveRequest& r : requests_) {
    if (r.seq == seq) return &r;
  }
  return nullptr;
}

PlotSeries& LiveSession::AddPlot(const std::string& channel,
                                 const std::string& column, double window_s) {
  plots_.push_back(std::make_unique<PlotSeries>(channel, column, window_s));
  return *plots_.back();
}

void LiveSession::RemovePlot(size_t index) {
  if (index < plots_.size()) {
    plots_.erase(plots_.begin() + static_cast<std::ptrdiff_t>(index));
  }
}

std::vector<std::string> LiveSession::Columns(
    const std::string& channel) const {
  std::vector<std::string> numeric;
  const auto it = readers_.find(channel);
  if (it == readers_.end()) return numeric;
  const ChannelReader& reader = *it->second;
  std::vector<std::string_view> cells;
  SplitCells(reader.row.values, &cells);
  const auto& cols = reader.flattener->columns();
  for (size_t i = 0; i < cols.size() && i < cells.size(); ++i) {
    if (cols[i] != "time" && cols[i] != "seq" && ParseNumber(cells[i])) {
      numeric.push_back(cols[i]);
    }
  }
  return numeric;
}

std::vector<std::string> LiveSession::Channels() const {
  std::vector<std::string> names;
  for (const auto& [name, reader] : readers_) names.push_back(name);
  return names;
}

}  // namespace mrsim::studio
