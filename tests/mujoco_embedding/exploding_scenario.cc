#include "tests/mujoco_embedding/exploding_scenario.h"

#include "sim_core/scenario/chain_builder.h"

namespace mrsim::testing {

Scenario ExplodingScenario() {
  Scenario s;
  s.settings.timestep = 0.5;
  ChainOptions options;
  options.modules = 4;
  options.module_mass = 1e-5;
  options.kp = 1e5;
  options.max_vel = 1000;
  s.robots.push_back(MakeChain(options));
  return s;
}

}  // namespace mrsim::testing
