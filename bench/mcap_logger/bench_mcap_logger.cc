// Benchmark: a 50-module robot's state at 1 kHz (bench_logger's stream),
// recorded at the same time by mrsim-log --mcap (protobuf in zstd chunks) and
// by lcm-logger (raw .lcmlog, the baseline), in rounds. Both hear the same
// datagrams in the same seconds, so each round is a pair (paired_ratio.h):
//   BENCH mcap_logger_cpu_ratio <median> x   CPU of mrsim-log --mcap over
//                                            lcm-logger's; target <= 1.5
//   BENCH mcap_logger_cpu_ratio_spread <X> %
//   BENCH mcap_logger_lost <n> msgs           sent but not in the MCAP file
// Rounds: --rounds N (default 6), each --seconds S (default 10; the
// start-up is counted: mrsim-log's, about 0.1 s of CPU while it loads
// OpenCV through the camera codec, is some 5 % of a 10 s round), or
// $MRSIM_BENCH_MCAP_ROUNDS / $MRSIM_BENCH_MCAP_SECONDS. --mcap-compression
// C and --mcap-encoding E (protobuf or json) are passed on to mrsim-log
// (default: its own, zstd and protobuf); each round prints both files'
// sizes, the other side of that choice.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/common/paired_ratio.h"
#include "common/subprocess.h"
#include "mrsim/robot_state_t.hpp"

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kModules = 50;
constexpr int kRateHz = 1000;
const char* const kChannel = "MRSIM_STATE_bench";
const char* const kUrl =
    "udpm://239.255.76.67:8120?ttl=0&recv_buf_size=8388608";

class Child {
 public:
  Child(const std::vector<std::string>& argv, const std::string& out_path)
      : out_path_(out_path),
        process_(argv, mrsim::SpawnOptions::ToFile(out_path)) {}
  double Stop(int sig, double timeout_s) {
    process_.Signal(sig);
    exit_code_ = process_.Wait(timeout_s);
    if (exit_code_ == -1) process_.Stop(0);
    return process_.cpu_seconds();
  }
  std::string Output() const {
    std::ifstream in(out_path_);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  int exit_code() const { return exit_code_; }

 private:
  std::string out_path_;
  mrsim::Subprocess process_;
  int exit_code_ = -1;
};

mrsim::pose_t Pose(double t, int i) {
  mrsim::pose_t p;
  p.position[0] = 0.1 * i + 0.01 * t;
  p.position[1] = 0.02 * std::sin(t + i);
  p.position[2] = 0.05 + 0.01 * std::cos(t + 0.3 * i);
  const double a = 0.5 * std::sin(2 * t + i);
  p.orientation[0] = std::cos(a / 2);
  p.orientation[1] = 0;
  p.orientation[2] = std::sin(a / 2);
  p.orientation[3] = 0;
  return p;
}

// bench_logger's state: 50 modules, 100 frames, 50 joints, 2 sensor
// modules with 6 distance sensors, 49 locks.
mrsim::robot_state_t State(int64_t seq) {
  const double t = static_cast<double>(seq) / kRateHz;
  mrsim::robot_state_t m;
  m.utime = seq * (1000000 / kRateHz);
  m.seq = seq;
  m.robot = "bench";
  m.sim_time = t;
  m.num_modules = kModules;
  m.num_frames = 2 * kModules;
  m.num_joints = kModules;
  for (int i = 0; i < kModules; ++i) {
    m.modules.push_back(Pose(t, i));
    m.frames.push_back(Pose(t + 0.001, i));
    m.frames.push_back(Pose(t + 0.002, i));
    mrsim::joint_state_t j;
    j.angle = std::sin(2 * M_PI * t / 4 + 2.5 * i);
    j.speed = std::cos(2 * M_PI * t / 4 + 2.5 * i);
    j.torque = 0.3 * j.angle;
    j.world = Pose(t, i);
    m.joints.push_back(j);
  }
  m.num_sensor_modules = 2;
  for (int s = 0; s < 2; ++s) {
    mrsim::sensor_module_state_t sm{};
    sm.pose = Pose(t, 100 + s);
    sm.has_force = true;
    sm.force = 4.9 + std::sin(t);
    sm.num_distances = 6;
    for (int f = 0; f < 6; ++f) {
      sm.distance.push_back(2.0 - 0.01 * t + 0.1 * f);
      sm.distance_face.push_back(static_cast<int8_t>(f));
    }
    m.sensor_modules.push_back(sm);
  }
  m.num_locks = kModules - 1;
  for (int k = 0; k < m.num_locks; ++k) {
    m.lock_names.push_back("bench/lock" + std::to_string(k));
    m.lock_attached.push_back(true);
  }
  for (int k = 0; k < 3; ++k) {
    m.com[k] = 0.01 * t * (k + 1);
    m.com_velocity[k] = 0.01 * (k + 1);
  }
  return m;
}

bool WaitFor(const Child& c, const std::string& text, double timeout_s) {
  const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (Clock::now() < end) {
    if (c.Output().find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// "N written" of the state channel in mrsim-log's summary, -1 if absent.
int64_t Written(const std::string& output) {
  const std::string key = std::string(kChannel) + ": mrsim.robot_state_t, ";
  const size_t at = output.find(key);
  if (at == std::string::npos) return -1;
  const size_t messages = output.find(" messages, ", at);
  if (messages == std::string::npos) return -1;
  return std::atoll(output.c_str() + messages + 11);
}

struct Round {
  double ours = 0, theirs = 0;
  int64_t lost = 0;
  int64_t mcap_bytes = 0, lcmlog_bytes = 0;
};

Round RunRound(const std::filesystem::path& dir, int round, double seconds,
               const std::string& compression, const std::string& encoding) {
  const std::string tag = std::to_string(round);
  std::vector<std::string> argv = {
      MRSIM_LOG_EXE,
      "--lcm-url",
      kUrl,
      "--mcap",
      (dir / ("run" + tag + ".mcap")).string(),
      "--channels",
      kChannel,
  };
  if (!compression.empty()) {
    argv.insert(argv.end(), {"--mcap-compression", compression});
  }
  if (!encoding.empty()) argv.insert(argv.end(), {"--mcap-encoding", encoding});
  Child ours(argv, (dir / ("mrsim-log" + tag + ".txt")).string());
  Child theirs({"/usr/bin/lcm-logger", std::string("--lcm-url=") + kUrl,
                (dir / ("run" + tag + ".lcmlog")).string()},
               (dir / ("lcm-logger" + tag + ".txt")).string());
  if (!WaitFor(ours, "recording channels", 30)) {
    throw std::runtime_error("mrsim-log did not start: " + ours.Output());
  }
  // lcm-logger says nothing when it listens; it is up well within this.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  lcm::LCM lcm(kUrl);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM");
  const int64_t total = static_cast<int64_t>(seconds * kRateHz);
  const auto start = Clock::now();
  const auto period = std::chrono::microseconds(1000000 / kRateHz);
  for (int64_t seq = 0; seq < total; ++seq) {
    std::this_thread::sleep_until(start + seq * period);
    const mrsim::robot_state_t msg = State(seq);
    lcm.publish(kChannel, &msg);
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  Round r;
  r.ours = ours.Stop(SIGTERM, 60);
  r.theirs = theirs.Stop(SIGINT, 30);
  if (ours.exit_code() != 0) {
    throw std::runtime_error("mrsim-log --mcap exited with " +
                             std::to_string(ours.exit_code()) + ": " +
                             ours.Output());
  }
  r.lost = total - Written(ours.Output());
  std::error_code ec;
  r.mcap_bytes = static_cast<int64_t>(
      std::filesystem::file_size(dir / ("run" + tag + ".mcap"), ec));
  r.lcmlog_bytes = static_cast<int64_t>(
      std::filesystem::file_size(dir / ("run" + tag + ".lcmlog"), ec));
  std::filesystem::remove(dir / ("run" + tag + ".mcap"), ec);
  std::filesystem::remove(dir / ("run" + tag + ".lcmlog"), ec);
  return r;
}

double Setting(int argc, char** argv, const char* flag, const char* env,
               double fallback) {
  double v = fallback;
  if (const char* e = std::getenv(env)) v = std::atof(e);
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == flag) v = std::atof(argv[i + 1]);
  }
  return v;
}

// The value after `flag` on the command line, or fallback.
std::string TextSetting(int argc, char** argv, const char* flag,
                        const std::string& fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == flag) return argv[i + 1];
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds =
      Setting(argc, argv, "--seconds", "MRSIM_BENCH_MCAP_SECONDS", 10);
  // --mcap-compression X is passed on to mrsim-log (default: its own).
  const std::string compression =
      TextSetting(argc, argv, "--mcap-compression", "");
  const std::string encoding = TextSetting(argc, argv, "--mcap-encoding", "");
  const int rounds = static_cast<int>(
      Setting(argc, argv, "--rounds", "MRSIM_BENCH_MCAP_ROUNDS", 6));
  if (!(seconds > 0) || rounds < 1) {
    std::fprintf(stderr, "bench_mcap_logger: --seconds > 0, --rounds >= 1\n");
    return 2;
  }
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::path(MRSIM_BENCH_DIR) / ("run_" + std::to_string(getpid()));
  fs::create_directories(dir);
  int status = 0;
  try {
    std::vector<double> ours, theirs;
    int64_t lost = 0;
    for (int i = 0; i < rounds; ++i) {
      const Round r = RunRound(dir, i, seconds, compression, encoding);
      std::fprintf(stderr,
                   "bench_mcap_logger: round %d: mrsim-log --mcap %.2f s CPU, "
                   "lcm-logger %.2f s CPU, %lld lost; files %.1f MB MCAP, "
                   "%.1f MB lcmlog\n",
                   i + 1, r.ours, r.theirs, static_cast<long long>(r.lost),
                   static_cast<double>(r.mcap_bytes) / 1e6,
                   static_cast<double>(r.lcmlog_bytes) / 1e6);
      ours.push_back(r.ours);
      theirs.push_back(r.theirs);
      lost += r.lost;
    }
    mrsim::PrintBench("mcap_logger_cpu_ratio",
                      mrsim::SummarizePairs(ours, theirs), "x",
                      "mrsim-log --mcap CPU s / lcm-logger CPU s");
    std::printf("BENCH mcap_logger_lost %lld msgs\n",
                static_cast<long long>(lost));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mcap_logger: %s\n", e.what());
    status = 1;
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return status;
}
