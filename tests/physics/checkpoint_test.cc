#include "sim_core/physics/checkpoint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "sim_core/scenario/chain_builder.h"
#include "tests/common/child_process.h"
#include "tests/physics/test_scenes.h"

namespace mrsim {
namespace {

void Drive(Physics& physics, double seconds) {
  std::vector<double> targets(physics.joint_count(0));
  const int steps = static_cast<int>(std::lround(seconds / physics.timestep()));
  for (int i = 0; i < steps; ++i) {
    for (size_t j = 0; j < targets.size(); ++j) {
      targets[j] = 1.2 * std::sin(2 * M_PI * physics.time() / 1.5 + 2.5 * j);
    }
    physics.SetJointTargets(0, targets);
    physics.Step();
  }
}

std::vector<unsigned char> Bytes(const double* v, int n) {
  const auto* p = reinterpret_cast<const unsigned char*>(v);
  return std::vector<unsigned char>(p, p + n * sizeof(double));
}

Scenario Snake(const std::string& dir) {
  Scenario s = testing::FlatScenario();
  s.base_dir = dir;
  testing::WriteGreyPng(dir + "/bumps.png", 30, 30, [](int r, int c) {
    return static_cast<int>(100 + 60 * std::sin(r * 0.7) * std::cos(c * 0.5));
  });
  s.scene.height_image = "bumps.png";
  s.scene.height = 0.05;
  s.scene.position = Eigen::Vector3d(-1.0, -0.75, -0.05);
  ChainOptions options;
  options.modules = 6;
  options.pattern = ChainPattern::kPitchYaw;
  options.sensor_after = {-1, 2};
  options.force_sensors = true;
  options.front_distance_sensor = true;
  options.origin = Eigen::Vector3d(0, 0, 0.05);
  s.robots.push_back(MakeChain(options));
  FluidRegion water;
  water.position = Eigen::Vector3d(0.5, 0, 0);
  water.size = Eigen::Vector3d(0.6, 2, 0.2);
  s.fluid_regions.push_back(water);
  return s;
}

TEST(Checkpoint, ResumeIsBitIdentical) {
  const std::string dir = testing::TempDir("checkpoint_resume");
  Physics original(Snake(dir));
  Drive(original, 2.0);
  const std::string path = dir + "/run.ckpt";
  SaveCheckpoint(path, original);
  const double saved_time = original.time();
  Drive(original, 2.0);

  std::unique_ptr<Physics> resumed = LoadCheckpoint(path);
  ASSERT_EQ(resumed->time(), saved_time);
  Drive(*resumed, 2.0);
  const mjModel* m = original.model();
  ASSERT_EQ(resumed->model()->nq, m->nq);
  EXPECT_EQ(resumed->time(), original.time());
  EXPECT_EQ(Bytes(resumed->data()->qpos, m->nq),
            Bytes(original.data()->qpos, m->nq));
  EXPECT_EQ(Bytes(resumed->data()->qvel, m->nv),
            Bytes(original.data()->qvel, m->nv));
  EXPECT_EQ(resumed->SaveState(), original.SaveState());
  // It really moved in between.
  EXPECT_GT(
      (original.CenterOfMass(0) - Physics(Snake(dir)).CenterOfMass(0)).norm(),
      0.001);
}

// A controller whose targets depend on everything ReadRobotState returns
// (angles, speeds, torques, CoM, forces, distances), read once per control
// period of 5 steps, as a real controller process does.
// `reads` > 1 reads the state that many times per period (the last one is
// used), which must not change the run.
void DriveFromState(Physics& physics, double seconds, int reads = 1) {
  const int steps = static_cast<int>(std::lround(seconds / physics.timestep()));
  std::vector<double> targets(physics.joint_count(0));
  for (int i = 0; i < steps; i += 5) {
    RobotState s = physics.ReadRobotState(0);
    for (int r = 1; r < reads; ++r) s = physics.ReadRobotState(0);
    double sensed = 0;
    for (const SensorModuleState& sm : s.sensor_modules) {
      sensed += 0.01 * sm.force;
      for (double d : sm.distances) sensed += 0.1 * d;
    }
    for (size_t j = 0; j < targets.size(); ++j) {
      const JointState& next = s.joints[(j + 1) % s.joints.size()];
      targets[j] = 0.5 * std::sin(2 * s.time + 2.5 * j + next.angle) +
                   0.1 * s.com.x() + 0.05 * s.com_velocity.y() +
                   0.02 * next.speed + 0.05 * s.joints[j].torque + sensed;
    }
    physics.SetJointTargets(0, targets);
    physics.Step(5);
  }
}

TEST(Checkpoint, ResumeWithStateDependentControllerIsBitIdentical) {
  const std::string dir = testing::TempDir("checkpoint_feedback");
  Physics original(Snake(dir));
  DriveFromState(original, 2.0);
  const std::string text = SaveCheckpointString(original);
  DriveFromState(original, 2.0);

  std::unique_ptr<Physics> resumed = LoadCheckpointString(text, "feedback");
  DriveFromState(*resumed, 2.0);
  const mjModel* m = original.model();
  ASSERT_EQ(resumed->model()->nq, m->nq);
  EXPECT_EQ(resumed->time(), original.time());
  EXPECT_EQ(std::memcmp(resumed->data()->qpos, original.data()->qpos,
                        m->nq * sizeof(double)),
            0);
  EXPECT_EQ(std::memcmp(resumed->data()->qvel, original.data()->qvel,
                        m->nv * sizeof(double)),
            0);
  EXPECT_EQ(resumed->SaveState(), original.SaveState());
  // The torque read right after a load is the one the original reports.
  EXPECT_NE(original.ReadRobotState(0).joints[0].torque, 0.0);
}

TEST(Checkpoint, ReadingTheStateDoesNotChangeTheRun) {
  const std::string dir = testing::TempDir("checkpoint_reads");
  Physics once(Snake(dir));
  Physics thrice(Snake(dir));
  DriveFromState(once, 1.0, 1);
  DriveFromState(thrice, 1.0, 3);
  EXPECT_EQ(thrice.SaveState(), once.SaveState());
}

TEST(Checkpoint, LoadedStateReadsBackAsTheOriginal) {
  const std::string dir = testing::TempDir("checkpoint_readback");
  Physics original(Snake(dir));
  DriveFromState(original, 1.0);
  std::unique_ptr<Physics> copy =
      LoadCheckpointString(SaveCheckpointString(original), "readback");
  const RobotState a = original.ReadRobotState(0);
  const RobotState b = copy->ReadRobotState(0);
  ASSERT_EQ(a.joints.size(), b.joints.size());
  for (size_t j = 0; j < a.joints.size(); ++j) {
    EXPECT_EQ(b.joints[j].angle, a.joints[j].angle) << "joint " << j;
    EXPECT_EQ(b.joints[j].speed, a.joints[j].speed) << "joint " << j;
    EXPECT_EQ(b.joints[j].torque, a.joints[j].torque) << "joint " << j;
  }
  EXPECT_EQ(b.com, a.com);
  EXPECT_EQ(b.com_velocity, a.com_velocity);
  ASSERT_EQ(a.sensor_modules.size(), b.sensor_modules.size());
  for (size_t k = 0; k < a.sensor_modules.size(); ++k) {
    EXPECT_EQ(b.sensor_modules[k].force, a.sensor_modules[k].force);
    EXPECT_EQ(b.sensor_modules[k].distances, a.sensor_modules[k].distances);
  }
  EXPECT_NE(a.joints[0].torque, 0.0);
}

TEST(Checkpoint, VersionOneStateStillLoads) {
  const std::string dir = testing::TempDir("checkpoint_v1");
  Physics original(Snake(dir));
  Drive(original, 0.3);
  const mjModel* m = original.model();
  const mjData* d = original.data();
  // The first format: no nsensordata, integrated qpos, torques, sensordata.
  std::vector<unsigned char> v1 = {'M', 'R', 'S', 'I', 'M', 'S', 'T', '1'};
  const int32_t sizes[6] = {m->nq, m->nv,    m->na,
                            m->nu, m->nbody, original.joint_count(0)};
  const auto* size_bytes = reinterpret_cast<const unsigned char*>(sizes);
  v1.insert(v1.end(), size_bytes, size_bytes + sizeof(sizes));
  auto put = [&v1](const double* v, int n) {
    const std::vector<unsigned char> b = Bytes(v, n);
    v1.insert(v1.end(), b.begin(), b.end());
  };
  put(&d->time, 1);
  put(d->qpos, m->nq);
  put(d->qvel, m->nv);
  put(d->act, m->na);
  put(d->ctrl, m->nu);
  put(d->qacc_warmstart, m->nv);
  put(d->qfrc_applied, m->nv);
  put(d->xfrc_applied, 6 * m->nbody);
  put(original.joint_targets(0).data(), original.joint_count(0));

  Physics loaded(Snake(dir));
  loaded.LoadState(v1);
  EXPECT_EQ(loaded.time(), original.time());
  EXPECT_EQ(Bytes(loaded.data()->qpos, m->nq), Bytes(d->qpos, m->nq));
  EXPECT_EQ(Bytes(loaded.data()->qvel, m->nv), Bytes(d->qvel, m->nv));
  EXPECT_EQ(loaded.joint_targets(0), original.joint_targets(0));
  v1.pop_back();
  EXPECT_THROW(loaded.LoadState(v1), std::invalid_argument);
}

// tests/physics/data holds two checkpoints mrsim-sim wrote (version-4 state)
// before the state's arrays were listed in one table
// (sim_core/physics/physics_state_fields.h): the run of scenarios/imu_snake.xml at
// 0.2 s and, from the same start, at 0.3 s. Loading the first and stepping
// on must give the second bit for bit.
TEST(Checkpoint, OneWrittenBeforeTheStateTableStillLoads) {
  const std::string data = testing::SourcePath("tests/physics/data/");
  std::unique_ptr<Physics> early =
      LoadCheckpoint(data + "imu_snake_t0.2_v4.checkpoint");
  std::unique_ptr<Physics> late =
      LoadCheckpoint(data + "imu_snake_t0.3_v4.checkpoint");
  EXPECT_EQ(early->time(), 0.20000000000000015);
  const int steps = static_cast<int>(
      std::lround((late->time() - early->time()) / early->timestep()));
  ASSERT_EQ(steps, 50);
  early->Step(steps);
  EXPECT_EQ(early->time(), late->time());
  EXPECT_EQ(early->SaveState(), late->SaveState());
}

TEST(Checkpoint, StringFormIsSelfContained) {
  const std::string dir = testing::TempDir("checkpoint_string");
  Physics original(Snake(dir));
  Drive(original, 0.5);
  const std::string text = SaveCheckpointString(original);
  EXPECT_EQ(text.rfind("mrsim-checkpoint 1\n", 0), 0u);
  // The terrain image travels inside: delete it, still loads.
  std::remove((dir + "/bumps.png").c_str());
  std::unique_ptr<Physics> copy = LoadCheckpointString(text, "sent");
  EXPECT_EQ(copy->SaveState(), original.SaveState());
  Drive(original, 0.2);
  Drive(*copy, 0.2);
  EXPECT_EQ(copy->SaveState(), original.SaveState());
}

TEST(Checkpoint, DamagedCheckpointIsRejectedWithItsName) {
  const std::string dir = testing::TempDir("checkpoint_damaged");
  Physics original(Snake(dir));
  std::string text = SaveCheckpointString(original);
  EXPECT_THROW(LoadCheckpointString("hello", "x.ckpt"), CheckpointError);
  try {
    LoadCheckpointString(text.substr(0, text.size() - 10), "cut.ckpt");
    FAIL() << "expected CheckpointError";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.ckpt"), std::string::npos);
  }
  EXPECT_THROW(LoadCheckpoint(dir + "/missing.ckpt"), CheckpointError);
}

TEST(Checkpoint, AStateNoRunCanHaveIsRefused) {
  const std::string dir = testing::TempDir("checkpoint_hostile_state");
  Physics original(Snake(dir));
  Drive(original, 0.1);
  const std::vector<unsigned char> good = original.SaveState();
  // The sim time is stored as its own double: find and replace it.
  const double time = original.time();
  const std::vector<unsigned char> pattern = Bytes(&time, 1);
  const auto at =
      std::search(good.begin(), good.end(), pattern.begin(), pattern.end());
  ASSERT_NE(at, good.end());
  for (const double bad : {std::nan(""), -1.0, 1e308}) {
    std::vector<unsigned char> state = good;
    std::memcpy(state.data() + (at - good.begin()), &bad, sizeof(bad));
    Physics copy(Snake(dir));
    try {
      copy.LoadState(state);
      ADD_FAILURE() << "loaded a sim time of " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("the sim time"), std::string::npos)
          << e.what();
    }
  }
  const std::string big = dir + "/big.ckpt";
  std::ofstream(big) << "mrsim-checkpoint 1\n";
  std::filesystem::resize_file(big, (size_t{128} << 20) + 1);
  try {
    LoadCheckpoint(big);
    ADD_FAILURE() << "loaded it";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find(big + ": larger than 128 MiB"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mrsim
