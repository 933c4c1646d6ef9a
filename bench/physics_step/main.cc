// Step rate of the 11-module pitch snake through Physics::Step (targets
// from a sinusoid every step) next to a bare mj_step loop on the exported
// MJCF doing the same servo arithmetic, in the same run. Rates are per
// second of this thread's CPU time (other processes on a busy machine do
// not count against either side); rounds alternate and the best round of
// each counts. Then the step time per module of pitch-yaw chains of 10 to
// 200 modules (a sensor module after each), and how far the timestep moves
// the result of a gait (scenarios/snake11.xml, 2 ms over 0.5 ms).
#include <mujoco/mujoco.h>

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
#include "sim_core/chain_builder.h"
#include "sim_core/mjcf_builder.h"
#include "sim_core/physics.h"
#include "sim_core/scenario_xml.h"

namespace {

constexpr int kSteps = 10000;  // per round: 20 s of simulated time
constexpr int kRounds = 9;
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

// Microseconds of CPU per module per step of a pitch-yaw chain of `n`
// modules with a sensor module after each, running a travelling wave.
double UsPerModuleStep(int n) {
  mrsim::Scenario s = Snake();
  mrsim::ChainOptions options;
  options.modules = n;
  options.pattern = mrsim::ChainPattern::kPitchYaw;
  for (int i = 0; i < n; ++i) options.sensor_after.push_back(i);
  s.robots[0] = mrsim::MakeChain(options);
  mrsim::Physics physics(s);
  std::vector<double> targets(physics.joint_count(0));
  const double omega = 2 * M_PI / kPeriod;
  auto run = [&](int steps) {
    for (int i = 0; i < steps; ++i) {
      const double t = physics.time();
      for (size_t j = 0; j < targets.size(); ++j) {
        targets[j] =
            j % 2 ? 0.0 : kAmplitude * std::sin(omega * t + kPhase * j);
      }
      physics.SetJointTargets(0, targets);
      physics.Step();
    }
  };
  run(500);  // the wave lifts the chain off its resting contacts
  double best = 1e300;
  const int steps = std::max(200, 20000 / n);
  for (int round = 0; round < 3; ++round) {
    const double start = CpuNow();
    run(steps);
    best = std::min(best, (CpuNow() - start) / steps);
  }
  return 1e6 * best / n;
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

// Optional argument: run one part only (ratio, modules, convergence).
int main(int argc, char** argv) {
  const std::string only = argc > 1 ? argv[1] : "";
  if (!only.empty() && only != "ratio" && only != "modules" &&
      only != "convergence") {
    std::fprintf(stderr,
                 "bench_physics_step: unknown part '%s' (expected ratio, "
                 "modules or convergence)\n",
                 only.c_str());
    return 2;
  }
  if (only.empty() || only == "ratio") RunRatio();
  if (only.empty() || only == "modules") {
    for (int n : {10, 50, 100, 200}) {
      std::printf("BENCH physics_us_per_module_step_%d %.2f us\n", n,
                  UsPerModuleStep(n));
      std::fflush(stdout);
    }
  }
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
