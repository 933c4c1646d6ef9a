// BENCH friction_overhead: CPU time per Physics::Step of a 10-module yaw
// snake doing lateral undulation with a directional ground entry (the
// staged pipeline rewriting every ground contact) over the same scenario
// with the entry isotropic (MuJoCo's own mj_step1). The directional
// coefficients equal the isotropic friction, so both runs touch the same
// contacts and only the cost differs. Alternating rounds, best of each,
// thread CPU time so other load on the machine does not skew the ratio.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"

namespace {

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

mrsim::Scenario Snake(bool directional) {
  mrsim::ChainScenarioOptions o;
  o.chain.modules = 10;
  o.chain.pattern = mrsim::ChainPattern::kYaw;
  o.friction = 0.6;
  mrsim::Scenario s = mrsim::MakeChainScenario(o);
  mrsim::ContactFriction& c = s.contact_frictions.at(0);
  c.directional = directional;
  c.forward_friction = c.backward_friction = c.lateral_friction = c.friction;
  return s;
}

// Seconds of CPU per step over `steps` steps of undulation.
double SecondsPerStep(const mrsim::Scenario& s, int steps) {
  mrsim::Physics physics(s);
  const int n = physics.joint_count(0);
  std::vector<double> targets(n);
  const double start = ThreadSeconds();
  for (int i = 0; i < steps; ++i) {
    const double t = physics.time();
    for (int j = 0; j < n; ++j) {
      targets[j] = 0.6 * std::sin(2 * M_PI * t / 1.5 - j * 2 * M_PI / n);
    }
    physics.SetJointTargets(0, targets);
    physics.Step();
  }
  return (ThreadSeconds() - start) / steps;
}

}  // namespace

int main() {
  const mrsim::Scenario plain = Snake(false);
  const mrsim::Scenario directional = Snake(true);
  double best_plain = 1e9, best_directional = 1e9;
  for (int round = 0; round < 5; ++round) {
    best_plain = std::min(best_plain, SecondsPerStep(plain, 3000));
    best_directional =
        std::min(best_directional, SecondsPerStep(directional, 3000));
  }
  std::printf("isotropic %.2f us/step, directional %.2f us/step\n",
              1e6 * best_plain, 1e6 * best_directional);
  std::printf("BENCH friction_overhead %.3f x\n",
              best_directional / best_plain);
  return 0;
}
