// mrsim-camera's speed, in the same run:
//   BENCH camera_fps <f> frames/s   pictures of one 160x120 RGB camera per
//     second through CameraNode (pose from the state, render on the CPU
//     with llvmpipe, read back, encode the message), from the states of a
//     moving case-study robot; target >= 30. The median of short repeats,
//     with the spread of that median.
//   BENCH camera_sim_slowdown <r> x  mrsim-sim's real-time factor on the
//     case study (realtime clock) with a 30 Hz camera process running over
//     without, in interleaved pairs (bench/common/paired_ratio.h); target
//     >= 0.95.
// --seconds S (default 4): simulated seconds of each simulator run;
// --pairs N (default 6).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/common/paired_ratio.h"
#include "bench/common/sim_report.h"
#include "camera/camera_node.h"
#include "camera/state_camera_renderer.h"
#include "common/subprocess.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

constexpr int kFramesPerRepeat = 10;
constexpr int kRepeats = 31;
const char* const kUrl = "udpm://239.255.76.67:8235?ttl=0";

// The case study with one 160x120, 30 Hz camera on its first sensor
// module's front face.
Scenario CaseStudyWithCamera() {
  Scenario s = ReadScenarioFile(std::string(MRSIM_SOURCE_DIR) +
                                "/scenarios/case_study.xml");
  if (s.robots.empty() || s.robots[0].sensor_modules.empty()) {
    throw std::runtime_error("case_study.xml: no sensor module");
  }
  Camera camera;
  camera.width = 160;
  camera.height = 120;
  camera.rate = 30;
  s.robots[0].sensor_modules[0].cameras = {camera};
  return s;
}

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void CameraFps(const Scenario& scenario) {
  // States of the robot as it settles and moves: each picture its own.
  Physics physics(scenario);
  std::vector<robot_state_t> states;
  for (int k = 0; k < kFramesPerRepeat * kRepeats + 1; ++k) {
    states.push_back(ToRobotStateMessage(physics.ReadRobotState(0), k));
    physics.Step(4);
  }
  StateCameraRenderer renderer(scenario);
  CameraNodeOptions options;
  options.clock = ClockMode::kLockstep;
  // A camera as fast as the states, so every state is a frame.
  std::vector<double> fps, cpu_fps;
  const std::string channel =
      StateChannel(options.prefix, renderer.robots()[0]);
  CameraNode node(options, &renderer, WallClock::now());
  CameraOutbox out;
  size_t next = 0;
  auto frame = [&] {
    robot_state_t s = states[next % states.size()];
    s.seq = static_cast<int64_t>(next);
    s.sim_time = static_cast<double>(next) / 30;  // a frame time: always due
    s.utime = SimTimeToUtime(s.sim_time);
    ++next;
    node.OnState(channel, s, WallClock::now(), &out);
    out.clear();
  };
  frame();  // warm-up: first-use allocations in Mesa
  for (int r = 0; r < kRepeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = CpuSeconds();
    for (int k = 0; k < kFramesPerRepeat; ++k) frame();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    fps.push_back(kFramesPerRepeat / wall);
    cpu_fps.push_back(kFramesPerRepeat / (CpuSeconds() - cpu_start));
  }
  const double median = Median(fps);
  std::printf(
      "# camera_fps: %d repeats of %d frames, 160x120 rgb8, renderer %s; "
      "per CPU second %.1f; pictures %lld\n",
      kRepeats, kFramesPerRepeat, "llvmpipe/EGL", Median(cpu_fps),
      static_cast<long long>(node.counters().pictures));
  std::printf("BENCH camera_fps %.1f frames/s\n", median);
  std::printf("BENCH camera_fps_spread %.1f %%\n",
              100 * RelativeMedianInterval(fps));
}

// One realtime run of the simulator (with the camera process or not);
// returns its real-time factor.
double SimRun(const std::string& scenario, double seconds, bool camera,
              int run) {
  const std::string dir = MRSIM_BENCH_DIR;
  std::optional<Subprocess> child;
  const std::string camera_log =
      dir + "/camera_" + std::to_string(run) + ".log";
  if (camera) {
    child.emplace(
        std::vector<std::string>{MRSIM_CAMERA_EXE, "--scenario", scenario,
                                 "--lcm-url", kUrl, "--clock", "realtime",
                                 "--exit-with-sim"},
        SpawnOptions::ToFile(camera_log));
  }
  const std::string sim_log = dir + "/sim_" + std::to_string(run) + ".log";
  Subprocess sim({MRSIM_SIM_EXE, scenario, "--lcm-url", kUrl, "--clock",
                  "realtime", "--duration", std::to_string(seconds)},
                 SpawnOptions::ToFile(sim_log));
  if (sim.Wait(seconds * 10 + 60) != 0) {
    throw std::runtime_error("mrsim-sim failed: see " + sim_log);
  }
  if (child) {
    if (child->Wait(30) != 0) {
      throw std::runtime_error("mrsim-camera failed: see " + camera_log);
    }
  }
  return ReadRealTimeFactor(sim_log);
}

void SimSlowdown(const Scenario& scenario, double seconds, int pairs) {
  const std::string path = std::string(MRSIM_BENCH_DIR) + "/camera_case.xml";
  WriteScenarioFile(scenario, path);
  int run = 0;
  const PairedRatio r =
      RunPaired([&] { return SimRun(path, seconds, true, run++); },
                [&] { return SimRun(path, seconds, false, run++); }, pairs);
  std::fputs(FormatBench("camera_sim_slowdown", r, "x",
                         "real-time factor with camera / without")
                 .c_str(),
             stdout);
}

}  // namespace
}  // namespace mrsim

int main(int argc, char** argv) {
  double seconds = 4;
  int pairs = 6;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--seconds") seconds = std::atof(argv[i + 1]);
    if (flag == "--pairs") pairs = std::atoi(argv[i + 1]);
  }
  try {
    const mrsim::Scenario scenario = mrsim::CaseStudyWithCamera();
    mrsim::CameraFps(scenario);
    std::fflush(stdout);
    mrsim::SimSlowdown(scenario, seconds, pairs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_camera: %s\n", e.what());
    return 1;
  }
  return 0;
}
