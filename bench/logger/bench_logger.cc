// Benchmark: a 50-module robot's state at 1 kHz, recorded at the same time
// by mrsim-log (CSV) and by lcm-logger (raw .lcmlog, the baseline). Prints
//   BENCH logger_lost <n> msgs        messages sent but not in the CSV
//   BENCH logger_cpu_ratio <r> x      CPU time of mrsim-log / lcm-logger
// Duration: --seconds S or $MRSIM_BENCH_LOGGER_SECONDS (default 60). The
// files (about 1.8 GB of CSV a minute) are deleted unless
// $MRSIM_BENCH_LOGGER_KEEP is set.
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

#include "common/subprocess.h"
#include "mrsim/robot_state_t.hpp"

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kModules = 50;
constexpr int kSensorModules = 2;
constexpr int kRateHz = 1000;
const char* const kChannel = "MRSIM_STATE_bench";
// Both recorders get the same large kernel receive buffer.
const char* const kUrl =
    "udpm://239.255.76.67:7930?ttl=0&recv_buf_size=8388608";

// A recorder process, its output in a file; its CPU time is read when it
// ends.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const std::string& out_path)
      : out_path_(out_path),
        process_(argv, mrsim::SpawnOptions::ToFile(out_path)) {}
  // Sends `sig` and waits (SIGKILL after timeout_s); returns user+system
  // CPU seconds.
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
  m.num_sensor_modules = kSensorModules;
  for (int s = 0; s < kSensorModules; ++s) {
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
  m.num_locks = kModules - 1;  // what the simulator sends for a chain
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

int64_t CountLines(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return 0;
  std::vector<char> buf(1 << 20);
  int64_t n = 0;
  size_t got = 0;
  while ((got = std::fread(buf.data(), 1, buf.size(), f)) > 0) {
    for (size_t i = 0; i < got; ++i) n += buf[i] == '\n';
  }
  std::fclose(f);
  return n;
}

int64_t CountLogEvents(const std::string& path) {
  lcm::LogFile log(path, "r");
  if (!log.good()) return 0;
  int64_t n = 0;
  while (const lcm::LogEvent* ev = log.readNextEvent()) {
    if (ev->channel == kChannel) ++n;
  }
  return n;
}

bool WaitFor(const Child& c, const std::string& text, double timeout_s) {
  const auto end = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (Clock::now() < end) {
    if (c.Output().find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 60;
  if (const char* env = std::getenv("MRSIM_BENCH_LOGGER_SECONDS")) {
    seconds = std::atof(env);
  }
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--seconds") seconds = std::atof(argv[i + 1]);
  }
  if (!(seconds > 0)) {
    std::fprintf(stderr, "bench_logger: duration must be positive\n");
    return 2;
  }
  namespace fs = std::filesystem;
  // In the build tree, not /tmp: a minute is about 2.5 GB, too much for a
  // RAM-backed /tmp.
  const fs::path dir =
      fs::path(MRSIM_BENCH_DIR) / ("run_" + std::to_string(getpid()));
  fs::create_directories(dir);
  int status = 0;
  try {
    Child ours({MRSIM_LOG_EXE, "--lcm-url", kUrl, "--out",
                (dir / "csv").string(), "--channels", kChannel},
               (dir / "mrsim-log.txt").string());
    Child theirs({"/usr/bin/lcm-logger", std::string("--lcm-url=") + kUrl,
                  (dir / "bench.lcmlog").string()},
                 (dir / "lcm-logger.txt").string());
    if (!WaitFor(ours, "recording channels", 30)) {
      throw std::runtime_error("mrsim-log did not start: " + ours.Output());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));

    lcm::LCM lcm(kUrl);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM");
    const int64_t total = static_cast<int64_t>(seconds * kRateHz);
    std::fprintf(stderr,
                 "bench_logger: %d-module state (%d bytes) at %d Hz for %g s\n",
                 kModules, State(0).getEncodedSize(), kRateHz, seconds);
    const auto start = Clock::now();
    const auto period = std::chrono::microseconds(1000000 / kRateHz);
    int64_t late = 0;
    for (int64_t seq = 0; seq < total; ++seq) {
      const auto due = start + seq * period;
      if (Clock::now() > due + 5 * period) ++late;
      std::this_thread::sleep_until(due);
      const mrsim::robot_state_t msg = State(seq);
      lcm.publish(kChannel, &msg);
      if (seq > 0 && seq % (10 * kRateHz) == 0) {
        std::fprintf(stderr, "bench_logger: %lld / %lld sent\n",
                     static_cast<long long>(seq),
                     static_cast<long long>(total));
      }
    }
    const double send_s =
        std::chrono::duration<double>(Clock::now() - start).count();
    std::this_thread::sleep_for(std::chrono::seconds(1));
    const double our_cpu = ours.Stop(SIGTERM, 60);
    const double their_cpu = theirs.Stop(SIGINT, 30);

    const int64_t rows = std::max<int64_t>(
        0,
        CountLines((dir / "csv" / (std::string(kChannel) + ".csv")).string()) -
            1);
    const int64_t logged = CountLogEvents((dir / "bench.lcmlog").string());
    if (ours.exit_code() != 0) {
      std::fprintf(stderr, "bench_logger: mrsim-log exited with %d:\n%s\n",
                   ours.exit_code(), ours.Output().c_str());
      status = 1;
    }
    std::fprintf(stderr,
                 "bench_logger: sent %lld in %.1f s (%lld late), "
                 "mrsim-log %lld rows in %.2f s CPU, lcm-logger %lld events "
                 "in %.2f s CPU\n",
                 static_cast<long long>(total), send_s,
                 static_cast<long long>(late), static_cast<long long>(rows),
                 our_cpu, static_cast<long long>(logged), their_cpu);
    std::printf("BENCH logger_lost %lld msgs\n",
                static_cast<long long>(total - rows));
    std::printf("BENCH logger_cpu_ratio %.2f x\n",
                their_cpu > 0 ? our_cpu / their_cpu : 0.0);
    std::printf("BENCH logger_cpu %.3f s_per_s\n", our_cpu / send_s);
    std::printf("BENCH lcm_logger_cpu %.3f s_per_s\n", their_cpu / send_s);
    std::printf("BENCH lcm_logger_lost %lld msgs\n",
                static_cast<long long>(total - logged));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_logger: %s\n", e.what());
    status = 1;
  }
  if (std::getenv("MRSIM_BENCH_LOGGER_KEEP") != nullptr) {
    std::fprintf(stderr, "bench_logger: kept %s\n", dir.c_str());
  } else {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  return status;
}
