// Step rate of the 11-module pitch snake through Physics::Step (targets
// from a sinusoid every step) next to a bare mj_step loop on the exported
// MJCF doing the same servo arithmetic, in the same run. Rates are per
// second of this thread's CPU time (other processes on a busy machine do
// not count against either side); rounds alternate and the best round of
// each counts.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <vector>

#include "sim_core/chain_builder.h"
#include "sim_core/mjcf_builder.h"
#include "sim_core/physics.h"

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

}  // namespace

int main() {
  const mrsim::Scenario scenario = Snake();
  const std::string path =
      (std::filesystem::temp_directory_path() / "bench_physics_step.xml")
          .string();
  std::ofstream(path) << mrsim::BuildMjcf(scenario);
  char error[1000] = {0};
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    std::fprintf(stderr, "bench_physics_step: %s: %s\n", path.c_str(), error);
    return 1;
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
  return 0;
}
