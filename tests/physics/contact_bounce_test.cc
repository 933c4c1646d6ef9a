// Restitution on real MuJoCo contacts: a dropped box rebounds by about its
// material pair's restitution, at the default step and at a finer one, and
// never gains energy (docs/physics.md, "Contacts").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim_core/physics/physics.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

constexpr double kDropHeight = 0.3;  // m, of the box's bottom face
constexpr double kBox = 0.05;        // m

// Drops a 5 cm box on flat ground with `restitution` between "plastic"
// and "ground" and returns the apex of its first rebound (m, bottom face
// above the ground).
double FirstReboundHeight(double restitution, double timestep) {
  Scenario s = testing::FlatScenario();
  s.contact_frictions[0].restitution = restitution;
  s.settings.timestep = timestep;
  s.robots.push_back(testing::SensorModuleRobot(
      "box", Eigen::Vector3d(0, 0, kDropHeight + kBox / 2)));
  Physics physics(s);
  bool landed = false;
  double apex = 0;
  double previous_vz = 0;
  while (physics.time() < 1.5) {
    physics.Step();
    const RobotState state = physics.ReadRobotState(0);
    const double vz = state.com_velocity.z();
    const double bottom = state.com.z() - kBox / 2;
    if (!landed && vz > 0) landed = true;
    if (landed) {
      apex = std::max(apex, bottom);
      if (previous_vz > 0 && vz <= 0) break;  // the first apex
    }
    previous_vz = vz;
  }
  return apex;
}

TEST(PhysicsContact, DroppedBoxReboundsByItsRestitution) {
  for (double e : {0.3, 0.5, 0.8}) {
    for (double timestep : {0.002, 0.0005}) {
      SCOPED_TRACE(::testing::Message()
                   << "restitution " << e << ", step " << timestep << " s");
      const double h = FirstReboundHeight(e, timestep);
      // Speed after over before the impact: sqrt of the heights' ratio.
      // Measured 0.43 / 0.39, 0.58 / 0.55, 0.82 / 0.81 (2 ms / 0.5 ms);
      // with the damping ratio alone carrying the restitution (a stiffer
      // spring for a bouncier pair) 1.78, 4.84 and 20.6 at 2 ms.
      const double measured = std::sqrt(h / kDropHeight);
      EXPECT_NEAR(measured, e, 0.15);
    }
  }
}

}  // namespace
}  // namespace mrsim
