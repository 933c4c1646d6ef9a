// Safe decoding against lcm-gen's: a 50-module robot_state_t (what
// mrsim-sim sends every control period) decoded over and over into one
// message, with DecodeMessage (the generated wire check first) and with
// lcm-gen's decode alone, in interleaved pairs of short batches
// (bench/common/paired_ratio.h). Prints BENCH decode_ratio (safe over
// lcm-gen's, the median of the pairs; the target is <= 1.2) with its spread,
// and the median time of each per message.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "bench/common/paired_ratio.h"
#include "lcmtypes/runtime/decode.h"
#include "mrsim/robot_state_t.hpp"

namespace {

using mrsim::robot_state_t;

mrsim::pose_t Pose(double v) {
  mrsim::pose_t p;
  for (int k = 0; k < 3; ++k) p.position[k] = v + k;
  for (int k = 0; k < 4; ++k) p.orientation[k] = 0.5 * v - k;
  return p;
}

// As mrsim-sim fills it for a 50-module chain with two sensor modules.
robot_state_t FiftyModules() {
  const int modules = 50;
  robot_state_t m{};
  m.utime = 123456;
  m.seq = 12;
  m.robot = "snake";
  m.sim_time = 0.123456;
  m.num_modules = modules;
  m.num_frames = 2 * modules;
  m.num_joints = modules - 1;
  for (int i = 0; i < modules; ++i) {
    m.modules.push_back(Pose(i));
    m.frames.push_back(Pose(i + 0.25));
    m.frames.push_back(Pose(i + 0.75));
  }
  for (int i = 0; i < m.num_joints; ++i) {
    mrsim::joint_state_t j{};
    j.angle = 0.01 * i;
    j.speed = 0.1;
    j.torque = 0.2;
    j.world = Pose(i + 0.5);
    m.joints.push_back(j);
  }
  m.num_sensor_modules = 2;
  for (int s = 0; s < 2; ++s) {
    mrsim::sensor_module_state_t sm{};
    sm.pose = Pose(s);
    sm.has_force = 1;
    sm.force = 1.5;
    sm.num_distances = 2;
    sm.distance = {0.3, 0.4};
    sm.distance_face = {0, 4};
    m.sensor_modules.push_back(sm);
  }
  m.num_locks = modules - 1;
  for (int k = 0; k < m.num_locks; ++k) {
    m.lock_names.push_back("snake/lock" + std::to_string(k));
    m.lock_attached.push_back(1);
  }
  return m;
}

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// CPU time of this thread, not wall time: on a shared machine a batch the
// scheduler parks for a few ms would otherwise read twice as slow (single
// pairs then scattered over 0.2-20 x with 0.4 cores free).
template <class Fn>
double SecondsPerCall(int calls, Fn fn) {
  const double start = ThreadCpuSeconds();
  for (int i = 0; i < calls; ++i) fn();
  return (ThreadCpuSeconds() - start) / calls;
}

}  // namespace

int main() {
  const robot_state_t msg = FiftyModules();
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  robot_state_t out;
  int failures = 0;
  auto safe = [&] {
    failures += mrsim::DecodeMessage(bytes.data(), bytes.size(), &out) ? 0 : 1;
  };
  auto plain = [&] {
    failures += out.decode(bytes.data(), 0, static_cast<int>(bytes.size())) ==
                        static_cast<int>(bytes.size())
                    ? 0
                    : 1;
  };
  safe();  // warm: the message's vectors reach their size once
  plain();
  // Many short pairs (about 15 ms of CPU a batch, 4.5 s in all) rather than a
  // few long ones: a batch a neighbour's burst hit is one pair of 150, which
  // the median leaves out, where it was one round of seven before.
  const int calls = 4000;
  const int pairs = 150;
  const mrsim::PairedRatio r =
      mrsim::RunPaired([&] { return SecondsPerCall(calls, safe); },
                       [&] { return SecondsPerCall(calls, plain); }, pairs);
  if (failures != 0) {
    std::fprintf(stderr, "bench_decode: %d decodes failed\n", failures);
    return 1;
  }
  mrsim::PrintBench("decode_ratio", r, "x", "s per decode, safe / lcm-gen");
  std::printf("BENCH decode_safe_us %.3f us\n", r.median_a * 1e6);
  std::printf("BENCH decode_lcmgen_us %.3f us\n", r.median_b * 1e6);
  std::printf("BENCH decode_message_bytes %zu bytes\n", bytes.size());
  return 0;
}
