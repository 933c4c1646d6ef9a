// mjData memory: MuJoCo 2.2 zeroes njmax-sized constraint arrays it may
// never use; MakeMjData / ResetMjData give those pages back without
// changing any result.
#include "sim_core/mujoco/mujoco_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/physics/physics.h"
#include "tests/common/mujoco_test.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

Scenario LongChain(int modules) {
  Scenario s = testing::FlatScenario();
  ChainOptions chain;
  chain.modules = modules;
  chain.pattern = ChainPattern::kPitchYaw;
  s.robots.push_back(MakeChain(chain));
  return s;
}

void Wave(const mjModel* m, mjData* d, int step) {
  for (int k = 0; k < m->nu; ++k)
    d->ctrl[k] = 0.5 * std::sin(0.02 * step + 0.4 * k);
}

TEST(MujocoData, ConstraintBuffersAreNotResidentAfterMaking) {
  const MjModelPtr m = CompileScenarioModel(LongChain(60), MjcfOptions{});
  const MjDataPtr plain(mj_makeData(m.get()));
  const MjDataPtr lean = MakeMjData(m.get());
  ASSERT_TRUE(plain && lean);
  const size_t plain_bytes = ResidentConstraintBytes(m.get(), plain.get());
  EXPECT_GT(plain_bytes, 10u << 20);  // MuJoCo wrote zeros over all of it
  EXPECT_LT(ResidentConstraintBytes(m.get(), lean.get()), plain_bytes / 50);
}

TEST(MujocoData, SteppingGivesWhatPlainDataGivesBitForBit) {
  const MjModelPtr m = CompileScenarioModel(LongChain(40), MjcfOptions{});
  const MjDataPtr plain(mj_makeData(m.get()));
  const MjDataPtr lean = MakeMjData(m.get());
  for (int step = 0; step < 150; ++step) {
    Wave(m.get(), plain.get(), step);
    Wave(m.get(), lean.get(), step);
    mj_step(m.get(), plain.get());
    mj_step(m.get(), lean.get());
  }
  ASSERT_GT(lean->nefc, 0);
  ASSERT_EQ(lean->nefc, plain->nefc);
  EXPECT_EQ(std::memcmp(lean->qpos, plain->qpos, sizeof(mjtNum) * m->nq), 0);
  EXPECT_EQ(std::memcmp(lean->qvel, plain->qvel, sizeof(mjtNum) * m->nv), 0);
  EXPECT_EQ(std::memcmp(lean->efc_force, plain->efc_force,
                        sizeof(mjtNum) * lean->nefc),
            0);
  // The steps used a fraction of the arrays: most pages never came back.
  EXPECT_LT(ResidentConstraintBytes(m.get(), lean.get()),
            ResidentConstraintBytes(m.get(), plain.get()) / 4);

  // A reset writes zeros over everything again, and gives it back again.
  ResetMjData(m.get(), lean.get());
  mj_resetData(m.get(), plain.get());
  EXPECT_LT(ResidentConstraintBytes(m.get(), lean.get()),
            ResidentConstraintBytes(m.get(), plain.get()) / 50);
  mj_step(m.get(), plain.get());
  mj_step(m.get(), lean.get());
  EXPECT_EQ(std::memcmp(lean->qpos, plain->qpos, sizeof(mjtNum) * m->nq), 0);
}

TEST(MujocoData, APhysicsRunHoldsOnlyTheConstraintRowsItUses) {
  Physics physics(LongChain(60));
  physics.Step(20);
  const mjModel* m = physics.model();
  const size_t reserved = sizeof(mjtNum) * static_cast<size_t>(m->njmax) *
                          static_cast<size_t>(m->njmax);
  EXPECT_GT(physics.data()->nefc, 0);
  EXPECT_LT(ResidentConstraintBytes(m, physics.data()), reserved / 4);
  physics.Reset();
  EXPECT_LT(ResidentConstraintBytes(m, physics.data()), reserved / 50);
}

}  // namespace
}  // namespace mrsim
