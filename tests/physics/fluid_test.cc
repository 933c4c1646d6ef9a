// Water and air regions: buoyancy and drag.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

Scenario Pool(double box_mass) {
  Scenario s = testing::FlatScenario();
  FluidRegion water;
  water.guid = "pool";
  water.kind = FluidKind::kWater;
  water.position = Eigen::Vector3d(0, 0, 0.25);  // surface at z = 0.5
  water.size = Eigen::Vector3d(2, 2, 0.5);
  water.density = 1000;
  s.fluid_regions.push_back(water);
  SceneObject box;
  box.guid = "box";
  box.size = Eigen::Vector3d(0.1, 0.1, 0.1);
  box.position = Eigen::Vector3d(0, 0, 0.3);
  box.mass = box_mass;
  s.scene_objects.push_back(box);
  return s;
}

double BoxZ(const Physics& physics) {
  const int body = mj_name2id(physics.model(), mjOBJ_BODY, "scene/obj0");
  return physics.data()->xpos[3 * body + 2];
}

TEST(PhysicsFluid, LightBoxFloatsAtItsDensityDepth) {
  // 0.4 kg in 1 litre: density 400, so 40 % of it is under water.
  Physics physics(Pool(0.4));
  physics.Step(3000);  // 6 s
  const double submerged = 0.4 * 0.1;
  EXPECT_NEAR(BoxZ(physics), 0.5 - submerged + 0.05, 0.005);
  EXPECT_LT(std::abs(physics.data()->qvel[2]), 0.05);
}

TEST(PhysicsFluid, AChainFloatsByItsFramesVolumeAlone) {
  // Two modules: four 5 cm frames (0.5 l), the middle two sharing one
  // contact box that must not float too. 0.1 kg in 0.5 l is 20 % under.
  Scenario s = Pool(1.0);
  s.scene_objects.clear();
  ChainOptions options;
  options.modules = 2;
  options.module_mass = 0.05;
  options.origin = Eigen::Vector3d(0, 0, 0.3);
  s.robots.push_back(MakeChain(options));
  Physics physics(s);
  physics.Step(3000);  // 6 s
  for (const Pose& frame : physics.ReadRobotState(0).frames) {
    EXPECT_NEAR(frame.position.z(), 0.5 - 0.2 * 0.05 + 0.025, 0.0015);
  }
}

TEST(PhysicsFluid, HeavyBoxSinks) {
  Physics physics(Pool(3.0));
  physics.Step(2000);
  EXPECT_NEAR(BoxZ(physics), 0.05, 0.003);  // on the floor
}

TEST(PhysicsFluid, AirDragLimitsFallingSpeed) {
  Scenario s = testing::FlatScenario();
  FluidRegion air;
  air.kind = FluidKind::kAir;
  air.density = 1.2;
  air.viscosity = 1.8e-5;
  air.position = Eigen::Vector3d(0, 0, 50);
  air.size = Eigen::Vector3d(10, 10, 100);
  s.fluid_regions.push_back(air);
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.2, 0.2, 0.2);
  ball.mass = 0.01;
  ball.position = Eigen::Vector3d(0, 0, 90);
  s.scene_objects.push_back(ball);
  Physics physics(s);
  physics.Step(2500);  // 5 s
  // Terminal speed of the quadratic law: (m - rho V) g = 0.5 rho Cd A v^2
  // (Stokes drag is tiny here; buoyancy of this light ball is not).
  const double area = M_PI * 0.1 * 0.1;
  const double volume = 4.0 / 3.0 * M_PI * 0.001;
  const double terminal =
      std::sqrt((0.01 - 1.2 * volume) * 9.81 / (0.5 * 1.2 * area));
  EXPECT_NEAR(-physics.data()->qvel[2], terminal, 0.05 * terminal);
}

}  // namespace
}  // namespace mrsim
