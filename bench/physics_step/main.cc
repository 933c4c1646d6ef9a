// Step rate of the 11-module pitch snake through Physics::Step (targets
// from a sinusoid every step) next to a bare mj_step loop on the exported
// MJCF doing the same servo arithmetic, in the same run. Rates are per
// second of this thread's CPU time (other processes on a busy machine do
// not count against either side); rounds alternate and the best round of
// each counts. Then the step time per module of pitch-yaw chains of 10 to
// 200 modules (a sensor module after each), and how far the timestep moves
// the result of a gait (scenarios/snake11.xml, 2 ms over 0.5 ms).
// `bench_physics_step profile` prints where a long chain's step time goes.
#include <fcntl.h>
#include <mujoco/mujoco.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gait_controller/gait_presets.h"
#include "gait_controller/gait_runner.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"

namespace {

constexpr int kSteps = 10000;  // per round: 20 s of simulated time
constexpr int kRounds = 9;
constexpr const char* kSimPath = MRSIM_SIM_PATH;
constexpr double kAmplitude = 1.0, kPeriod = 4.0, kPhase = 2.5;

double CpuNow() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

mrsim::Scenario Snake() {
  mrsim::Scenario s;
  s.contact_frictions.push_back({"plastic", "ground", 0.0, 0.6, 2e9});
  s.contact_frictions.push_back({"plastic", "plastic", 0.0, 0.4, 2e9});
  mrsim::ChainOptions options;
  options.modules = 11;
  options.pattern = mrsim::ChainPattern::kPitch;
  s.robots.push_back(mrsim::MakeChain(options));
  return s;
}

double RunPhysics(const mrsim::Scenario& scenario) {
  mrsim::Physics physics(scenario);
  std::vector<double> targets(physics.joint_count(0));
  const double omega = 2 * M_PI / kPeriod;
  const double start = CpuNow();
  for (int i = 0; i < kSteps; ++i) {
    const double t = physics.time();
    for (size_t j = 0; j < targets.size(); ++j) {
      targets[j] = kAmplitude * std::sin(omega * t + kPhase * j);
    }
    physics.SetJointTargets(0, targets);
    physics.Step();
  }
  return kSteps / (CpuNow() - start);
}

double RunBare(const mjModel* m, const std::vector<double>& kp,
               const std::vector<double>& max_vel) {
  mjData* d = mj_makeData(m);
  std::vector<int> qpos(m->nu);
  for (int a = 0; a < m->nu; ++a) {
    qpos[a] = m->jnt_qposadr[m->actuator_trnid[2 * a]];
  }
  const double omega = 2 * M_PI / kPeriod;
  const double start = CpuNow();
  for (int i = 0; i < kSteps; ++i) {
    const double t = d->time;
    for (int a = 0; a < m->nu; ++a) {
      const double target = kAmplitude * std::sin(omega * t + kPhase * a);
      d->ctrl[a] = std::clamp(kp[a] * (target - d->qpos[qpos[a]]), -max_vel[a],
                              max_vel[a]);
    }
    mj_step(m, d);
  }
  const double rate = kSteps / (CpuNow() - start);
  mj_deleteData(d);
  return rate;
}

// The chain of the module benchmark: pitch-yaw, a sensor module after each
// module (so 3 boxes per module touch the ground at rest).
mrsim::Scenario LongChain(int n) {
  mrsim::Scenario s = Snake();
  mrsim::ChainOptions options;
  options.modules = n;
  options.pattern = mrsim::ChainPattern::kPitchYaw;
  for (int i = 0; i < n; ++i) options.sensor_after.push_back(i);
  s.robots[0] = mrsim::MakeChain(options);
  return s;
}

// Travelling wave on the pitch joints (even hinges) of every robot.
void Wave(mrsim::Physics& physics, std::vector<std::vector<double>>& targets) {
  const double omega = 2 * M_PI / kPeriod;
  const double t = physics.time();
  for (size_t r = 0; r < targets.size(); ++r) {
    for (size_t j = 0; j < targets[r].size(); ++j) {
      targets[r][j] =
          j % 2 ? 0.0 : kAmplitude * std::sin(omega * t + kPhase * j + r);
    }
    physics.SetJointTargets(static_cast<int>(r), targets[r]);
  }
}

// CPU seconds per step of `scenario` under the wave: `warmup` steps first
// (the wave lifts the chain off its resting contacts), best of 3 rounds.
double SecondsPerStep(const mrsim::Scenario& scenario, int warmup, int steps) {
  mrsim::Physics physics(scenario);
  std::vector<std::vector<double>> targets;
  for (int r = 0; r < physics.robot_count(); ++r) {
    targets.emplace_back(physics.joint_count(r));
  }
  auto run = [&](int n) {
    for (int i = 0; i < n; ++i) {
      Wave(physics, targets);
      physics.Step();
    }
  };
  run(warmup);
  double best = 1e300;
  for (int round = 0; round < 3; ++round) {
    const double start = CpuNow();
    run(steps);
    best = std::min(best, (CpuNow() - start) / steps);
  }
  return best;
}

// Microseconds of CPU per module per step of a LongChain of `n` modules.
double UsPerModuleStep(int n) {
  return 1e6 * SecondsPerStep(LongChain(n), 500, std::max(200, 20000 / n)) / n;
}

// The largest LongChain whose step takes less CPU than its timestep
// (bisection between module counts; `fast` steps in real time, `slow` not).
int RealtimeModules(int fast, int slow) {
  const double timestep = Snake().settings.timestep;
  while (slow - fast > std::max(2, fast / 50)) {
    const int mid = (fast + slow) / 2;
    const double s = SecondsPerStep(LongChain(mid), 300, 200);
    (s < timestep ? fast : slow) = mid;
  }
  return fast;
}

// `count` eleven-module pitch-yaw robots side by side, 0.3 m apart.
mrsim::Scenario Crowd(int count) {
  mrsim::Scenario s = Snake();
  s.robots.clear();
  const int columns = 10;
  for (int i = 0; i < count; ++i) {
    mrsim::ChainOptions options;
    options.name = "snake" + std::to_string(i);
    options.modules = 11;
    options.pattern = mrsim::ChainPattern::kPitchYaw;
    options.origin =
        Eigen::Vector3d(1.6 * (i / columns), 0.3 * (i % columns), 0);
    s.robots.push_back(mrsim::MakeChain(options));
  }
  return s;
}

void RunModules() {
  std::vector<std::pair<int, double>> us;
  for (int n : {10, 50, 100, 200, 400}) {
    try {
      us.emplace_back(n, UsPerModuleStep(n));
    } catch (const mrsim::PhysicsError& e) {
      // MuJoCo 2.2 holds at most MjcfMaxRows(nv) constraint rows in a world.
      std::printf("%d modules do not fit one MuJoCo 2.2 world: %s\n", n,
                  e.what());
      std::fflush(stdout);
      break;
    }
    std::printf("BENCH physics_us_per_module_step_%d %.2f us\n", n,
                us.back().second);
    std::fflush(stdout);
  }
  if (us.size() >= 4) {
    std::printf("BENCH physics_scaling_200 %.2f x\n",
                us[3].second / us[0].second);
  }
  const double timestep = Snake().settings.timestep;
  int fast = 1, slow = us.back().first + 1;
  for (const auto& [n, u] : us) {
    if (1e-6 * u * n < timestep) {
      fast = std::max(fast, n);
    } else {
      slow = std::min(slow, n);
    }
  }
  std::printf("BENCH realtime_modules %d modules\n",
              RealtimeModules(fast, std::max(slow, fast + 1)));
  std::fflush(stdout);
}

// Where the step's time goes (MuJoCo's own timers, CPU microseconds per
// step) for LongChains of 10 and 200 modules under the wave: no BENCH
// lines, a table for docs/physics.md ("Long chains and crowds").
mjtNum TimerMicroseconds() { return 1e6 * CpuNow(); }

void RunProfile() {
  mjcb_time = TimerMicroseconds;
  std::printf("%8s %4s %5s %5s %9s %9s %9s %9s %9s %6s\n", "modules", "nv",
              "ncon", "nefc", "step", "solver", "collision", "make", "rest",
              "iter");
  for (int n : {10, 200}) {
    mrsim::Physics physics(LongChain(n));
    std::vector<std::vector<double>> targets;
    for (int r = 0; r < physics.robot_count(); ++r) {
      targets.emplace_back(physics.joint_count(r));
    }
    for (int i = 0; i < 500; ++i) {
      Wave(physics, targets);
      physics.Step();
    }
    mjData* d = const_cast<mjData*>(physics.data());
    for (mjTimerStat& t : d->timer) t = mjTimerStat{};
    const int steps = std::max(200, 20000 / n);
    long iterations = 0, ncon = 0, nefc = 0;
    const double start = CpuNow();
    for (int i = 0; i < steps; ++i) {
      Wave(physics, targets);
      physics.Step();
      iterations += physics.data()->solver_iter;
      ncon += physics.data()->ncon;
      nefc += physics.data()->nefc;
    }
    const double step = 1e6 * (CpuNow() - start) / steps;
    auto per_step = [&](int timer) {
      return physics.data()->timer[timer].duration / steps;
    };
    const double solver = per_step(mjTIMER_CONSTRAINT);
    const double collision = per_step(mjTIMER_POS_COLLISION);
    const double make = per_step(mjTIMER_POS_MAKE);
    std::printf(
        "%8d %4d %5ld %5ld %7.0fus %7.0fus %7.0fus %7.0fus %7.0fus %6.1f\n", n,
        physics.model()->nv, ncon / steps, nefc / steps, step, solver,
        collision, make, step - solver - collision - make,
        static_cast<double>(iterations) / steps);
  }
  mjcb_time = nullptr;
}

void RunRobots() {
  double one = 0;
  for (int k : {1, 10, 25, 50}) {
    double us = 0;
    try {
      us = 1e6 * SecondsPerStep(Crowd(k), 300, std::max(100, 10000 / k)) / k;
    } catch (const mrsim::PhysicsError& e) {
      // MuJoCo 2.2 holds at most MjcfMaxRows(nv) constraint rows in a world.
      std::printf(
          "%d eleven-module robots do not fit one MuJoCo 2.2 world: %s\n", k,
          e.what());
      std::fflush(stdout);
      continue;
    }
    if (k == 1) one = us;
    std::printf("BENCH physics_us_per_robot_step_%d %.2f us\n", k, us);
    if (k > 1)
      std::printf("BENCH physics_scaling_robots_%d %.2f x\n", k, us / one);
    std::fflush(stdout);
  }
}

// This process's resident memory now, MB.
double ResidentMb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

// Peak resident memory (MB) of mrsim-sim running a plain 200-module pitch
// chain (`mrsim-scenario new --modules 200`) for 1 s of sim time.
void RunMemory() {
  mrsim::ChainScenarioOptions options;
  options.chain.modules = 200;
  options.friction = 0.6;
  const std::string path =
      (std::filesystem::temp_directory_path() / "bench_sim_rss_200.xml")
          .string();
  mrsim::WriteScenarioFile(mrsim::MakeChainScenario(options), path);
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open("/dev/null", O_WRONLY);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(kSimPath, kSimPath, path.c_str(), "--clock", "fast", "--duration",
          "1", "--no-state", "--lcm-url", "udpm://239.255.76.67:7667?ttl=0",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (pid < 0 || wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) ||
      WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "bench_physics_step: %s %s failed (status %d)\n",
                 kSimPath, path.c_str(), status);
    std::exit(1);
  }
  std::filesystem::remove(path);
  std::printf("BENCH sim_rss_mb_200 %.0f MB\n", usage.ru_maxrss / 1024.0);
  std::fflush(stdout);

  // What a Physics of the same chain holds once it runs: the peak above is
  // MuJoCo 2.2 writing zeros over its whole constraint buffer when it makes
  // the data; MakeMjData gives the unused pages back right after.
  const double before = ResidentMb();
  {
    mrsim::Physics physics(mrsim::MakeChainScenario(options));
    physics.Step(500);
    std::printf("BENCH physics_resident_mb_200 %.0f MB\n",
                ResidentMb() - before);
  }
  {
    mrsim::Physics physics(Crowd(50));
    physics.Step(100);
    std::printf("BENCH physics_resident_mb_robots_50 %.0f MB\n",
                ResidentMb() - before);
  }
  std::fflush(stdout);
}

// Horizontal CoM displacement of snake11 after `seconds` of `forward`.
double ForwardDisplacement(double timestep, double seconds) {
  mrsim::Scenario s = mrsim::ReadScenarioFile("scenarios/snake11.xml");
  s.settings.timestep = timestep;
  mrsim::Physics physics(s);
  mrsim::GaitController controller(mrsim::JointAxes(physics, 0));
  controller.SetGait(*mrsim::FindGaitPreset("forward"));
  controller.SetMotion(mrsim::Motion::kForward, 1.0);
  const mrsim::GaitRunResult r =
      mrsim::RunGait(physics, 0, controller, seconds, 0.01);
  const Eigen::Vector3d d = r.com_end - r.com_start;
  return std::hypot(d.x(), d.y());
}

}  // namespace

void RunRatio();

// Optional argument: run one part only (ratio, modules, robots, memory,
// convergence).
int main(int argc, char** argv) {
  const std::string only = argc > 1 ? argv[1] : "";
  if (!only.empty() && only != "ratio" && only != "modules" &&
      only != "robots" && only != "memory" && only != "convergence" &&
      only != "profile") {
    std::fprintf(stderr,
                 "bench_physics_step: unknown part '%s' (expected ratio, "
                 "modules, robots, memory, convergence or profile)\n",
                 only.c_str());
    return 2;
  }
  if (only == "profile") {
    RunProfile();
    return 0;
  }
  if (only.empty() || only == "ratio") RunRatio();
  if (only.empty() || only == "modules") RunModules();
  if (only.empty() || only == "robots") RunRobots();
  if (only.empty() || only == "memory") RunMemory();
  if (only.empty() || only == "convergence") {
    const double coarse = ForwardDisplacement(0.002, 10.0);
    const double fine = ForwardDisplacement(0.0005, 10.0);
    std::printf("snake11 forward 10 s: %.4f m at 2 ms, %.4f m at 0.5 ms\n",
                coarse, fine);
    std::printf("BENCH contact_step_convergence %.3f x\n", coarse / fine);
  }
  return 0;
}

void RunRatio() {
  const mrsim::Scenario scenario = Snake();
  const std::string path =
      (std::filesystem::temp_directory_path() / "bench_physics_step.xml")
          .string();
  std::ofstream(path) << mrsim::BuildMjcf(scenario);
  char error[1000] = {0};
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "bench_physics_step: %s: %s\n", path.c_str(), error);
    std::exit(1);
  }
  std::vector<double> kp, max_vel;
  for (const mrsim::Module& module : scenario.robots[0].modules) {
    kp.push_back(module.joint.kp);
    max_vel.push_back(module.joint.max_vel);
  }
  double best_physics = 0, best_bare = 0;
  for (int round = 0; round < kRounds; ++round) {
    best_bare = std::max(best_bare, RunBare(m, kp, max_vel));
    best_physics = std::max(best_physics, RunPhysics(scenario));
    std::printf("round %d: physics %.0f steps/s, bare mj_step %.0f steps/s\n",
                round, best_physics, best_bare);
    std::fflush(stdout);
  }
  mj_deleteModel(m);
  std::printf(
      "physics_step rate %.0f steps/s (Physics::Step, 11-module snake)\n",
      best_physics);
  std::printf("bare mj_step rate %.0f steps/s (same MJCF)\n", best_bare);
  std::printf("BENCH physics_step_ratio %.3f x\n", best_physics / best_bare);
  std::fflush(stdout);
}
