// The C++ baseline of python_step_ratio: Physics::Step(1000) repeated, as
// bench_python.py does through Simulation.step(1000). Prints the best
// seconds of one Step(1000) call.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "sim_core/physics.h"
#include "sim_core/scenario_xml.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: bench_python_step SCENARIO REPEATS\n");
    return 2;
  }
  try {
    mrsim::Physics physics(mrsim::ReadScenarioFile(argv[1]));
    const int repeats = std::stoi(argv[2]);
    physics.SetJointTargets(0,
                            std::vector<double>(physics.joint_count(0), 0.3));
    double best = 1e9;
    for (int r = 0; r < repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      physics.Step(1000);
      best = std::min(best, std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - start)
                                .count());
    }
    std::printf("%.9f\n", best);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_python_step: %s\n", e.what());
    return 1;
  }
  return 0;
}
