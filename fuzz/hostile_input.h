// Decodable but hostile messages built from fuzz input, for the node-core
// targets: a core only ever sees messages that passed the wire check, so
// the interesting inputs are well-formed ones with wrong robots, absurd
// sequence numbers, NaN and 1e308 everywhere, and array lengths that
// disagree with the scenario. The fuzzer picks each value from a short
// list of such values or takes raw bytes, so it finds them quickly.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "lcmtypes/runtime/decode.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/opt_chunk_request_t.hpp"
#include "mrsim/opt_chunk_t.hpp"
#include "mrsim/opt_heartbeat_t.hpp"
#include "mrsim/opt_job_t.hpp"
#include "mrsim/opt_result_t.hpp"
#include "mrsim/opt_run_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"

namespace mrsim::fuzz {

class HostileInput {
 public:
  HostileInput(const uint8_t* data, size_t size) : p_(data), left_(size) {}

  bool empty() const { return left_ == 0; }

  uint8_t Byte() {
    if (left_ == 0) return 0;
    --left_;
    return *p_++;
  }

  uint64_t Raw(size_t bytes) {
    uint64_t v = 0;
    for (size_t k = 0; k < bytes; ++k) v = (v << 8) | Byte();
    return v;
  }

  // An integer in [lo, hi] (hi - lo < 2^32).
  int64_t Between(int64_t lo, int64_t hi) {
    const uint64_t span = static_cast<uint64_t>(hi - lo) + 1;
    return lo + static_cast<int64_t>(Raw(4) % span);
  }

  bool Bool() { return (Byte() & 1) != 0; }

  double Double() {
    static const double kValues[] = {0.0,
                                     1.0,
                                     -1.0,
                                     0.5,
                                     std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     1e308,
                                     -1e308,
                                     std::numeric_limits<double>::denorm_min(),
                                     std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::lowest(),
                                     3.2,
                                     -3.2,
                                     1e9,
                                     0.01};
    const uint8_t pick = Byte();
    if (pick < 16 * 12) return kValues[pick % 16];
    const uint64_t bits = Raw(8);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }

  // A sequence number or count: near `near`, or absurd.
  int64_t Int(int64_t near = 0) {
    static const int64_t kValues[] = {0,
                                      1,
                                      -1,
                                      2,
                                      std::numeric_limits<int64_t>::max(),
                                      std::numeric_limits<int64_t>::min(),
                                      std::numeric_limits<int32_t>::max(),
                                      std::numeric_limits<int32_t>::min()};
    const uint8_t pick = Byte();
    if (pick < 64) return kValues[pick % 8];
    if (pick < 192) return near + static_cast<int64_t>(pick % 16) - 4;
    return static_cast<int64_t>(Raw(8));
  }

  // One of `known` (the right robot, a real sender), or a stranger.
  std::string Text(const std::vector<std::string>& known) {
    const uint8_t pick = Byte();
    if (!known.empty() && pick < 160) return known[pick % known.size()];
    if (pick < 200) return "";
    if (pick < 220) return std::string(Between(0, 300), 'x');
    std::string s(Byte() % 24, '\0');
    for (char& c : s) c = static_cast<char>(Byte());
    return s;
  }

  // An array length: the scenario's, off by a little, or zero.
  int32_t Length(int32_t expected, int32_t max) {
    const uint8_t pick = Byte();
    int64_t n = expected;
    if (pick >= 128 && pick < 192) n = expected + (pick % 5) - 2;
    if (pick >= 192 && pick < 224) n = 0;
    if (pick >= 224) n = Between(0, max);
    return static_cast<int32_t>(
        std::min<int64_t>(std::max<int64_t>(n, 0), max));
  }

  pose_t Pose() {
    pose_t p;
    for (double& v : p.position) v = Double();
    for (double& v : p.orientation) v = Double();
    return p;
  }

  robot_state_t RobotState(const std::vector<std::string>& robots,
                           int32_t modules, int64_t seq) {
    robot_state_t m{};
    m.utime = Int(seq * 10000);
    m.seq = Int(seq);
    m.robot = Text(robots);
    m.sim_time = Double();
    m.num_modules = Length(modules, 64);
    for (int i = 0; i < m.num_modules; ++i) m.modules.push_back(Pose());
    m.num_frames = Length(2 * modules, 128);
    for (int i = 0; i < m.num_frames; ++i) m.frames.push_back(Pose());
    m.num_joints = Length(modules, 64);
    for (int i = 0; i < m.num_joints; ++i) {
      joint_state_t j{};
      j.angle = Double();
      j.speed = Double();
      j.torque = Double();
      j.world = Pose();
      m.joints.push_back(j);
    }
    m.num_sensor_modules = Length(0, 4);
    for (int i = 0; i < m.num_sensor_modules; ++i) {
      sensor_module_state_t s{};
      s.pose = Pose();
      s.has_force = Bool();
      s.force = Double();
      s.num_distances = static_cast<int8_t>(Length(2, 8));
      for (int k = 0; k < s.num_distances; ++k) {
        s.distance.push_back(Double());
        s.distance_face.push_back(static_cast<int8_t>(Byte()));
      }
      m.sensor_modules.push_back(s);
    }
    for (double& v : m.com) v = Double();
    for (double& v : m.com_velocity) v = Double();
    m.num_locks = Length(modules > 0 ? modules - 1 : 0, 64);
    for (int i = 0; i < m.num_locks; ++i) {
      m.lock_names.push_back(Text({"snake/lock0", "lock1"}));
      m.lock_attached.push_back(Bool());
    }
    // Drawn last, so the seeds written before these fields keep their
    // meaning for everything above.
    for (double& v : m.orientation) v = Double();
    m.heading = Double();
    return m;
  }

  joint_command_t JointCommand(const std::vector<std::string>& robots,
                               const std::vector<std::string>& senders,
                               int32_t joints, int64_t state_seq) {
    joint_command_t m{};
    m.utime = Int();
    m.seq = Int(state_seq);
    m.robot = Text(robots);
    m.sender = Text(senders);
    m.state_seq = Int(state_seq);
    m.num_joints = Length(joints, 64);
    for (int i = 0; i < m.num_joints; ++i) m.target.push_back(Double());
    return m;
  }

  // Paths are never ones a core could write to: a fuzzer must not leave
  // files behind or overwrite any.
  std::string SafePath() {
    static const char* const kPaths[] = {"", "/nonexistent-mrsim-fuzz/x.ckpt",
                                         "/nonexistent-mrsim-fuzz/",
                                         "/dev/null/x", "/dev/null/x/"};
    return kPaths[Byte() % 5];
  }

  sim_control_t SimControl(const std::vector<std::string>& robots,
                           const std::vector<std::string>& senders) {
    sim_control_t m{};
    m.utime = Int();
    m.seq = Int(1);
    m.sender = Text(senders);
    m.command = static_cast<int8_t>(Byte() % 12);
    m.steps = static_cast<int32_t>(Int(1));
    m.speed = Double();
    m.path = SafePath();
    m.robot = Text(robots);
    m.lock = Text({"snake/lock0", "lock1"});
    return m;
  }

  sim_status_t SimStatus(int64_t seq) {
    sim_status_t m{};
    m.utime = Int(seq * 10000);
    m.seq = Int(seq);
    m.sim_time = Double();
    m.real_time_factor = Double();
    m.mode = static_cast<int8_t>(Byte() % 4);
    m.clock = Text({"lockstep", "realtime", "fast"});
    m.speed = Double();
    m.control_rate = Double();
    m.steps_per_period = static_cast<int32_t>(Int(10));
    m.steps = Int(seq);
    m.state_seq = Int(seq);
    m.control_seq = Int(1);
    m.control_sender = Text({"mrsim-studio", "g"});
    m.control_ok = Bool();
    m.last_error = Text({});
    return m;
  }

  gait_command_t GaitCommand(const std::vector<std::string>& robots) {
    gait_command_t m{};
    m.utime = Int();
    m.seq = Int(1);
    m.sender = Text({"mrsim-studio", "ctl"});
    m.robot = Text(robots);
    m.gait = Text({"forward", "sidewinding", "rolling", "turn"});
    m.has_parameters = Bool();
    for (double& v : m.parameters) v = Double();
    m.motion = Text({"forward", "backward", "turn-left", "stop", "roll"});
    m.strength = Double();
    m.has_direction = Bool();
    m.forward = Double();
    m.turn = Double();
    return m;
  }

  gait_status_t GaitStatus(const std::vector<std::string>& robots) {
    gait_status_t m{};
    m.utime = Int();
    m.seq = Int(1);
    m.robot = Text(robots);
    m.sender = Text({"g"});
    m.sim_time = Double();
    m.running = Bool();
    m.gait = Text({"forward"});
    m.kind = Text({"sine"});
    for (double& v : m.parameters) v = Double();
    m.motion = Text({"forward"});
    m.strength = Double();
    m.command_seq = Int(1);
    m.command_sender = Text({"mrsim-studio"});
    m.command_result = static_cast<int8_t>(Byte() % 5);
    m.command_error = Text({});
    m.warning = Text({});
    return m;
  }

  scene_state_t SceneState(int32_t objects) {
    scene_state_t m{};
    m.utime = Int();
    m.seq = Int(1);
    m.sim_time = Double();
    m.num_objects = Length(objects, 16);
    for (int i = 0; i < m.num_objects; ++i) {
      m.object_index.push_back(static_cast<int32_t>(Int(i)));
      m.poses.push_back(Pose());
    }
    return m;
  }

  opt_run_t Run(const std::string& run_id, const std::string& hash) {
    opt_run_t m{};
    m.utime = Int();
    m.run_id = Text({run_id});
    m.started = Int(1);
    m.heartbeat_period = Double();
    m.scenario_hash = Text({hash});
    m.payload_size = Int(100);
    m.chunk_count = static_cast<int32_t>(Int(2));
    m.chunk_size = static_cast<int32_t>(Int(64));
    m.copies = static_cast<int32_t>(Int(1));
    return m;
  }

  opt_chunk_t Chunk(const std::string& run_id, const std::string& hash) {
    opt_chunk_t m{};
    m.utime = Int();
    m.run_id = Text({run_id});
    m.scenario_hash = Text({hash});
    m.index = static_cast<int32_t>(Int(0));
    m.count = static_cast<int32_t>(Int(2));
    m.size = Length(64, 256);
    for (int i = 0; i < m.size; ++i) m.data.push_back(Byte());
    return m;
  }

  opt_job_t Job(const std::string& run_id, const std::string& hash,
                const std::string& worker, int32_t genes) {
    opt_job_t m{};
    m.utime = Int();
    m.run_id = Text({run_id});
    m.scenario_hash = Text({hash});
    m.worker_id = Text({worker});
    m.job_id = Int(1);
    m.generation = static_cast<int32_t>(Int(0));
    m.index = static_cast<int32_t>(Int(0));
    m.gene_count = Length(genes, 16);
    for (int i = 0; i < m.gene_count; ++i) m.genome.push_back(Double());
    return m;
  }

  opt_heartbeat_t Heartbeat(const std::vector<std::string>& workers,
                            const std::string& run_id,
                            const std::string& hash) {
    opt_heartbeat_t m{};
    m.utime = Int();
    m.worker_id = Text(workers);
    m.host = Text({"host"});
    m.pid = static_cast<int32_t>(Int(100));
    m.run_id = Text({run_id});
    m.scenario_hash = Text({hash});
    m.slots = static_cast<int32_t>(Int(1));
    m.job_count = Length(1, 8);
    for (int i = 0; i < m.job_count; ++i) m.jobs.push_back(Int(1));
    m.done_count = Length(1, 8);
    for (int i = 0; i < m.done_count; ++i) m.done.push_back(Int(1));
    m.jobs_done = Int();
    m.messages_ignored = Int();
    m.messages_malformed = Int();
    return m;
  }

  opt_result_t Result(const std::vector<std::string>& workers,
                      const std::string& run_id, const std::string& hash) {
    opt_result_t m{};
    m.utime = Int();
    m.run_id = Text({run_id});
    m.scenario_hash = Text({hash});
    m.worker_id = Text(workers);
    m.job_id = Int(1);
    m.generation = static_cast<int32_t>(Int(0));
    m.index = static_cast<int32_t>(Int(0));
    m.fitness = Double();
    m.distance = Double();
    m.speed = Double();
    m.energy = Double();
    m.drift = Double();
    m.fell = Double();
    m.failed = Bool();
    m.eval_seconds = Double();
    m.error = Text({});
    return m;
  }

  opt_chunk_request_t ChunkRequest(const std::vector<std::string>& workers,
                                   const std::string& run_id,
                                   const std::string& hash) {
    opt_chunk_request_t m{};
    m.utime = Int();
    m.run_id = Text({run_id});
    m.scenario_hash = Text({hash});
    m.worker_id = Text(workers);
    m.count = Length(2, 16);
    for (int i = 0; i < m.count; ++i) {
      m.missing.push_back(static_cast<int32_t>(Int(i)));
    }
    return m;
  }

  // A time step (s): usually small, sometimes a jump.
  double Step() {
    const uint8_t pick = Byte();
    if (pick < 200) return 0.001 * pick;
    return static_cast<double>(pick - 199) * 1.7;
  }

 private:
  const uint8_t* p_;
  size_t left_;
};

// What a receiving process would make of `msg`: encoded, then decoded as
// every receiver decodes (the wire check first). False when a receiver
// would drop it (a string over its maximum, say); the core never sees it.
template <class Message>
bool ThroughWire(Message* msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg->getEncodedSize()));
  if (msg->encode(bytes.data(), 0, static_cast<int>(bytes.size())) < 0) {
    return false;
  }
  Message decoded;
  if (!DecodeMessage(bytes.data(), bytes.size(), &decoded)) return false;
  *msg = std::move(decoded);
  return true;
}

}  // namespace mrsim::fuzz
