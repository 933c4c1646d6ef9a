// The physics state's table (sim_core/physics/physics_state_fields.h) is what every
// copy of the state carries: each array it lists for checkpoints comes back
// bit for bit from a save and a load, in one world and in a split scene.
#include "sim_core/physics/physics_state_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

Robot Chain(const std::string& name, const Eigen::Vector3d& origin) {
  ChainOptions options;
  options.name = name;
  options.modules = 5;
  options.origin = origin;
  options.sensor_after = {1};
  options.force_sensors = true;
  return MakeChain(options);
}

void Drive(Physics& physics, int steps) {
  for (int i = 0; i < steps; ++i) {
    for (int r = 0; r < physics.robot_count(); ++r) {
      std::vector<double> targets(physics.joint_count(r));
      for (size_t j = 0; j < targets.size(); ++j)
        targets[j] = std::sin(2 * M_PI * physics.time() + 1.5 * j + r);
      physics.SetJointTargets(r, targets);
    }
    physics.Step();
  }
}

std::vector<unsigned char> Array(const Physics& physics,
                                 const PhysicsStateField& f) {
  const mjtNum* v = physics.data()->*f.array;
  const int n = StateSize(physics.model(), f.per);
  const auto* b = reinterpret_cast<const unsigned char*>(v);
  return n == 0 ? std::vector<unsigned char>()
                : std::vector<unsigned char>(b, b + n * sizeof(mjtNum));
}

// Every mjData array of the checkpoint: the loaded physics holds what the
// saved one held. Returns how many were non-empty.
int ExpectSameArrays(const Physics& saved, const Physics& loaded) {
  int compared = 0;
  for (const PhysicsStateField& f : kPhysicsStateFields) {
    if (!(f.copies & kStateCheckpoint) || f.array == nullptr) continue;
    const std::vector<unsigned char> want = Array(saved, f);
    EXPECT_EQ(Array(loaded, f), want) << f.name;
    compared += !want.empty();
  }
  return compared;
}

// MuJoCo's own account of a simulation's state (its documentation's
// "simulation state": time, qpos, qvel, act, the warm start, the controls,
// applied forces, mocap poses and user data): every array of it is in the
// table, and a bigger mjData mid-step keeps all of them.
TEST(PhysicsStateTable, ListsEveryArrayOfMuJoCosState) {
  const std::pair<const char*, mjtNum * mjData::*> state[] = {
      {"qpos", &mjData::qpos},
      {"qvel", &mjData::qvel},
      {"act", &mjData::act},
      {"qacc_warmstart", &mjData::qacc_warmstart},
      {"ctrl", &mjData::ctrl},
      {"qfrc_applied", &mjData::qfrc_applied},
      {"xfrc_applied", &mjData::xfrc_applied},
      {"mocap_pos", &mjData::mocap_pos},
      {"mocap_quat", &mjData::mocap_quat},
      {"userdata", &mjData::userdata}};
  for (const auto& [name, array] : state) {
    bool grown = false;
    for (const PhysicsStateField& f : kPhysicsStateFields) {
      if (f.array == array) {
        EXPECT_STREQ(f.name, name);
        grown |= (f.copies & kStateGrow) != 0 ||
                 (f.array == &mjData::qpos);  // from qpos_integrated
      }
    }
    EXPECT_TRUE(grown) << name;
  }
}

TEST(PhysicsStateTable, EveryCheckpointArrayRoundTrips) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(Chain("snake", Eigen::Vector3d(0, 0, 0.05)));
  Physics original(s);
  Drive(original, 100);
  // A distinct offset on every entry of every array (as a poke between two
  // steps could leave it), so an array left out of save or load, or read
  // into another's place, shows.
  mjData* d = original.mutable_data();
  const mjModel* m = original.model();
  int k = 0;
  for (const PhysicsStateField& f : kPhysicsStateFields) {
    if (!(f.copies & kStateCheckpoint) || f.array == nullptr) continue;
    mjtNum* v = d->*f.array;
    const double step = f.per == StatePer::kJointPosition ? 1e-6 : 1e-4;
    for (int i = 0; i < StateSize(m, f.per); ++i) v[i] += step * ++k;
  }
  const std::vector<unsigned char> blob = original.SaveState();
  Physics loaded(s);
  loaded.LoadState(blob);
  EXPECT_EQ(loaded.time(), original.time());
  // qpos qvel ctrl qacc_warmstart qfrc_applied xfrc_applied actuator_force
  // sensordata qacc_smooth (this model has no activations).
  EXPECT_GE(ExpectSameArrays(original, loaded), 9);
  EXPECT_EQ(loaded.joint_targets(0), original.joint_targets(0));
  EXPECT_EQ(loaded.SaveState(), blob);
  // (The poked original would not continue as the loaded one: its
  // kinematics are those from before the poke. Checkpoint.* tests that a
  // loaded run continues bit for bit.)
}

TEST(PhysicsStateTable, EveryCheckpointArrayRoundTripsInASplitScene) {
  Scenario s = testing::FlatScenario();
  s.robots.push_back(Chain("near", Eigen::Vector3d(0, 0, 0.05)));
  s.robots.push_back(Chain("far", Eigen::Vector3d(0, 3, 0.05)));
  Physics original(s);
  Drive(original, 100);
  const std::vector<unsigned char> blob = original.SaveState();
  Physics loaded(s);
  loaded.LoadState(blob);
  EXPECT_EQ(loaded.time(), original.time());
  EXPECT_GE(ExpectSameArrays(original, loaded), 5);
  EXPECT_EQ(loaded.SaveState(), blob);
  Drive(original, 20);
  Drive(loaded, 20);
  EXPECT_EQ(loaded.SaveState(), original.SaveState());
}

}  // namespace
}  // namespace mrsim
