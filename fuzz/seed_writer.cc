// Writes the seed corpora of the decoder targets (lcm_decode, log_flatten):
// one real encoded message of every type, as mrsim's processes send them.
// Run by hand when a type changes:
//   cmake --build build --target mrsim_fuzz_seed_writer
//   build/fuzz/mrsim_fuzz_seed_writer fuzz/corpus
#include <bitset>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "mrsim/message_types.hpp"
#include "tests/logger/test_messages.h"

namespace {

// The type selector both targets read: the type's place in name order,
// from the list generated from the .lcm files.
template <class Message>
constexpr int kTypeIndex = -1;
#define MRSIM_TYPE_INDEX(T, I) \
  template <>                  \
  constexpr int kTypeIndex<mrsim::T> = I;
MRSIM_MESSAGE_TYPES(MRSIM_TYPE_INDEX)
#undef MRSIM_TYPE_INDEX

// Which types have a seed: every one must (main checks).
std::bitset<MRSIM_MESSAGE_TYPE_COUNT> written;

template <class Message>
void Write(const std::string& dir, const std::string& name,
           const Message& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  static_assert(kTypeIndex<Message> >= 0, "not a message type");
  const char selector = static_cast<char>(kTypeIndex<Message>);
  written.set(kTypeIndex<Message>);
  std::ofstream decode(dir + "/lcm_decode/" + name, std::ios::binary);
  decode.put(selector);
  decode.write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
  // log_flatten: the selector, then two datagrams (2-byte length each).
  std::ofstream flatten(dir + "/log_flatten/" + name, std::ios::binary);
  flatten.put(selector);
  for (int copy = 0; copy < 2; ++copy) {
    flatten.put(static_cast<char>(bytes.size() >> 8));
    flatten.put(static_cast<char>(bytes.size() & 0xff));
    flatten.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mrsim;
  if (argc != 2) {
    std::fprintf(stderr, "usage: mrsim_fuzz_seed_writer CORPUS_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  const robot_state_t state = testing::KnownRobotState(7, 5, 1);
  // A 4x2 picture as mrsim-camera sends one (rgb8: 3 bytes a pixel).
  camera_image_t image{};
  image.seq = 7;
  image.robot = "snake";
  image.sender = "mrsim-camera";
  image.name = "snake/sm0/camera";
  image.sim_time = 0.5;
  image.width = 4;
  image.height = 2;
  image.encoding = "rgb8";
  image.num_bytes = 4 * 2 * 3;
  for (int i = 0; i < image.num_bytes; ++i) {
    image.data.push_back(static_cast<uint8_t>(i * 10));
  }
  Write(dir, "camera_image_t", image);
  gait_command_t gc{};
  gc.seq = 3;
  gc.sender = "mrsim-ctl";
  gc.robot = "snake";
  gc.motion = "forward";
  gc.strength = 1;
  Write(dir, "gait_command_t", gc);
  gait_status_t gs{};
  gs.robot = "snake";
  gs.sender = "mrsim-gait";
  gs.gait = "forward";
  gs.kind = "sine";
  gs.motion = "forward";
  gs.running = 1;
  Write(dir, "gait_status_t", gs);
  joint_command_t jc{};
  jc.robot = "snake";
  jc.sender = "mrsim-gait";
  jc.state_seq = 7;
  jc.num_joints = 5;
  jc.target = {0.1, -0.2, 0.3, 0, 0.5};
  Write(dir, "joint_command_t", jc);
  Write(dir, "joint_state_t", state.joints[0]);
  opt_chunk_request_t cr{};
  cr.run_id = "run";
  cr.scenario_hash = "0123456789abcdef";
  cr.worker_id = "host-1";
  cr.count = 2;
  cr.missing = {0, 3};
  Write(dir, "opt_chunk_request_t", cr);
  opt_chunk_t ch{};
  ch.run_id = "run";
  ch.scenario_hash = "0123456789abcdef";
  ch.count = 4;
  ch.size = 16;
  ch.data.assign(16, 0x41);
  Write(dir, "opt_chunk_t", ch);
  opt_heartbeat_t hb{};
  hb.worker_id = "host-1";
  hb.host = "host";
  hb.run_id = "run";
  hb.scenario_hash = "0123456789abcdef";
  hb.slots = 2;
  hb.job_count = 2;
  hb.jobs = {4, 5};
  hb.done_count = 1;
  hb.done = {3};
  Write(dir, "opt_heartbeat_t", hb);
  opt_job_t job{};
  job.run_id = "run";
  job.scenario_hash = "0123456789abcdef";
  job.worker_id = "host-1";
  job.job_id = 4;
  job.gene_count = 3;
  job.genome = {0.5, 1.0, 0.25};
  Write(dir, "opt_job_t", job);
  opt_progress_t progress{};
  progress.seq = 2;
  progress.run_id = "run";
  progress.out_dir = "opt";
  progress.algorithm = "cmaes";
  progress.generation = 3;
  progress.generations = 20;
  progress.best = 1.5;
  progress.eta = "1m12s";
  progress.state = opt_progress_t::RUNNING;
  Write(dir, "opt_progress_t", progress);
  opt_result_t res{};
  res.run_id = "run";
  res.scenario_hash = "0123456789abcdef";
  res.worker_id = "host-1";
  res.job_id = 4;
  res.fitness = 1.5;
  Write(dir, "opt_result_t", res);
  opt_run_t run{};
  run.run_id = "run";
  run.scenario_hash = "0123456789abcdef";
  run.payload_size = 1000;
  run.chunk_count = 1;
  run.chunk_size = 1000;
  run.copies = 2;
  Write(dir, "opt_run_t", run);
  Write(dir, "pose_t", state.modules[0]);
  Write(dir, "robot_state_t", state);
  scene_state_t scene{};
  scene.num_objects = 1;
  scene.object_index = {0};
  scene.poses = {state.modules[1]};
  Write(dir, "scene_state_t", scene);
  Write(dir, "sensor_module_state_t", state.sensor_modules[0]);
  sensor_reading_t reading{};
  reading.kind = "imu";
  reading.face = -1;
  reading.num_values = 6;
  reading.values = {0, 0, 9.81, 0, 0, 0.5};
  Write(dir, "sensor_reading_t", reading);
  sim_control_t control{};
  control.seq = 1;
  control.sender = "mrsim-ctl";
  control.command = sim_control_t::STEP;
  control.steps = 10;
  Write(dir, "sim_control_t", control);
  sim_status_t status{};
  status.clock = "lockstep";
  status.control_sender = "mrsim-ctl";
  status.waiting_for = "mrsim-gait";
  Write(dir, "sim_status_t", status);
  if (!written.all()) {
    std::fprintf(stderr,
                 "mrsim_fuzz_seed_writer: %zu of %d message types "
                 "have no seed; add one for each new type\n",
                 MRSIM_MESSAGE_TYPE_COUNT - written.count(),
                 MRSIM_MESSAGE_TYPE_COUNT);
    return 1;
  }
  return 0;
}
