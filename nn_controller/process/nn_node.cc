#include "nn_controller/process/nn_node.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace mrsim {
namespace {

constexpr size_t kMaxLogLines = 1000;

}  // namespace

void ObservationOfMessage(const robot_state_t& state, NnObservation* out) {
  out->time = state.sim_time;
  const size_t n = state.joints.size();
  out->angles.resize(n);
  out->speeds.resize(n);
  for (size_t j = 0; j < n; ++j) {
    out->angles[j] = state.joints[j].angle;
    out->speeds[j] = state.joints[j].speed;
  }
  for (int i = 0; i < 4; ++i) out->orientation[i] = state.orientation[i];
  for (int i = 0; i < 3; ++i) out->com_velocity[i] = state.com_velocity[i];
  out->sensor_values.clear();
  for (const sensor_module_state_t& m : state.sensor_modules) {
    if (m.has_force) out->sensor_values.push_back(m.force);
    for (double d : m.distance) out->sensor_values.push_back(d);
  }
}

NnNode::NnNode(NnNodeOptions options, MlpNetwork network, WallTime now)
    : options_(std::move(options)),
      network_(std::move(network)),
      pacer_(options_.robot, options_.sender, options_.rate),
      watch_(
          fmt::format("{} or {}", StateChannel(options_.prefix, options_.robot),
                      SimStatusChannel(options_.prefix)),
          options_.exit_with_sim, now) {}

void NnNode::Log(std::string line) {
  if (log_.size() < kMaxLogLines) log_.push_back(std::move(line));
}

std::vector<std::string> NnNode::TakeLog() {
  std::vector<std::string> out;
  out.swap(log_);
  return out;
}

WallTime NnNode::Tick(WallTime now) {
  std::vector<std::string> lines;
  watch_.Tick(now, &lines);
  for (std::string& line : lines) Log(std::move(line));
  return AfterSeconds(now, 0.5);
}

void NnNode::OnSimStatus(const sim_status_t& status, WallTime now) {
  std::vector<std::string> lines;
  watch_.OnStatus(status, now, &lines);
  for (std::string& line : lines) Log(std::move(line));
}

void NnNode::OnState(const robot_state_t& state, WallTime now, NnOutbox* out) {
  watch_.Heard(now);
  if (!error_.empty()) return;
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
  if (state.num_joints != network_.shape().joints) {
    error_ =
        fmt::format("the network drives {} joints but robot {} has {}",
                    network_.shape().joints, options_.robot, state.num_joints);
    return;
  }
  if (!announced_) {
    announced_ = true;
    Log(fmt::format("robot {}: {} joints; running the network", options_.robot,
                    state.num_joints));
  }
  std::string note;
  const StatePacer::Decision decision =
      pacer_.Decide(state, watch_.may_be_lockstep(), &note);
  if (!note.empty()) Log(std::move(note));
  if (decision.verdict == StatePacer::Verdict::kRepeat) {
    ++counters_.states_repeated;
    out->Add(CommandChannel(options_.prefix, options_.robot), *decision.repeat);
    return;
  }
  if (decision.verdict == StatePacer::Verdict::kSkip) {
    ++counters_.states_skipped;
    return;
  }
  // The network has no memory: a reset (decision.restarted) needs nothing.
  ObservationOfMessage(state, &input_);
  std::vector<double> targets = network_.Evaluate(input_);
  out->Add(CommandChannel(options_.prefix, options_.robot),
           pacer_.Answer(state, std::move(targets)));
  ++counters_.states_answered;
}

std::string NnNode::Summary() const {
  const NnNodeCounters& n = counters_;
  return fmt::format(
      "{}: answered {} states ({} repeated, {} skipped), malformed messages "
      "{}",
      options_.robot, n.states_answered, n.states_repeated, n.states_skipped,
      n.messages_malformed);
}

}  // namespace mrsim
