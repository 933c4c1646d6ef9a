// MakeChain: the geometry documented in chain_builder.h, which the physics,
// gait and other components rely on.
#include "sim_core/scenario/chain_builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "sim_core/scenario/scenario_schema.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

constexpr double kEps = 1e-12;

ChainOptions Sensored(int modules) {
  ChainOptions o;
  o.name = "cs";
  o.modules = modules;
  o.pattern = ChainPattern::kPitchYaw;
  o.sensor_after = {-1};
  for (int i = 0; i < modules; ++i) o.sensor_after.push_back(i);
  o.force_sensors = true;
  o.front_distance_sensor = true;
  return o;
}

TEST(ChainBuilder, ModulesLieAlongXWithModuleZeroInFront) {
  ChainOptions o;
  o.modules = 5;
  o.origin = Eigen::Vector3d(1, 2, 0);
  const Robot r = MakeChain(o);
  ASSERT_EQ(r.modules.size(), 5u);
  EXPECT_EQ(r.name, "snake");
  EXPECT_NEAR(r.modules[0].position.x(), 1, kEps);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(r.modules[i].mod_nr, i);
    EXPECT_NEAR(r.modules[i].position.y(), 2, kEps);
    if (i > 0) {
      EXPECT_LT(r.modules[i].position.x(), r.modules[i - 1].position.x());
    }
  }
}

TEST(ChainBuilder, FramesTouchAndTheModulePositionIsTheirMidpoint) {
  ChainOptions o;
  o.modules = 4;
  o.frame_size = Eigen::Vector3d(0.06, 0.04, 0.03);
  const Robot r = MakeChain(o);
  for (size_t i = 0; i < r.modules.size(); ++i) {
    const Module& m = r.modules[i];
    const std::string prefix = "snake/m" + std::to_string(i);
    EXPECT_EQ(m.frames[0].guid, prefix + "/f0");
    EXPECT_EQ(m.frames[1].guid, prefix + "/f1");
    EXPECT_EQ(m.joint.guid, prefix + "/joint");
    EXPECT_EQ(m.joint.type, JointType::kHinge);
    EXPECT_EQ(m.joint.left_frame_guid, m.frames[0].guid);
    EXPECT_EQ(m.joint.right_frame_guid, m.frames[1].guid);
    // f0 in front, touching f1 at the hinge.
    EXPECT_NEAR(m.frames[0].position.x() - m.frames[1].position.x(), 0.06,
                kEps);
    EXPECT_TRUE(m.position.isApprox(
        (m.frames[0].position + m.frames[1].position) / 2, kEps));
    EXPECT_EQ(m.frames[0].scale, o.frame_size);
    EXPECT_NEAR(m.frames[0].mass + m.frames[1].mass, o.module_mass, kEps);
    if (i > 0) {  // the back face of one module touches the next's front
      EXPECT_NEAR(r.modules[i - 1].frames[1].position.x() - 0.03,
                  m.frames[0].position.x() + 0.03, kEps);
    }
  }
}

TEST(ChainBuilder, RestsOnTheGroundAtHalfTheFrameHeight) {
  ChainOptions o;
  o.frame_size = Eigen::Vector3d(0.05, 0.05, 0.04);
  o.origin = Eigen::Vector3d(0, 0, 0.5);
  const Robot r = MakeChain(o);
  for (const Module& m : r.modules) {
    EXPECT_NEAR(m.position.z(), 0.52, kEps);
    for (const Frame& f : m.frames) EXPECT_NEAR(f.position.z(), 0.52, kEps);
  }
  // With force plates the chain stands on them: plate bottom on the ground.
  const Robot s = MakeChain(Sensored(3));
  for (const SensorModule& sm : s.sensor_modules) {
    const ForceSensor& plate = *sm.force_sensor;
    EXPECT_NEAR(plate.position.z() - plate.size.z() / 2, 0, kEps);
    EXPECT_NEAR(sm.position.z() - sm.size.z() / 2,
                plate.position.z() + plate.size.z() / 2, kEps);
  }
}

TEST(ChainBuilder, PatternsSetTheAxes) {
  ChainOptions o;
  o.modules = 4;
  o.pattern = ChainPattern::kYaw;
  for (const Module& m : MakeChain(o).modules) EXPECT_EQ(m.axis, Axis::kYaw);
  o.pattern = ChainPattern::kPitch;
  for (const Module& m : MakeChain(o).modules) {
    EXPECT_EQ(m.axis, Axis::kPitch);
  }
  o.pattern = ChainPattern::kPitchYaw;
  const Robot r = MakeChain(o);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(r.modules[i].axis, i % 2 == 0 ? Axis::kPitch : Axis::kYaw);
  }
}

TEST(ChainBuilder, LocksJoinConsecutiveParts) {
  ChainOptions o;
  o.modules = 3;
  const Robot plain = MakeChain(o);
  ASSERT_EQ(plain.locks.size(), 2u);
  EXPECT_EQ(plain.locks[0].guid, "snake/lock0");
  EXPECT_EQ(plain.locks[0].type, JointType::kLock);
  EXPECT_EQ(plain.locks[0].left_frame_guid, "snake/m0/f1");
  EXPECT_EQ(plain.locks[0].right_frame_guid, "snake/m1/f0");
  EXPECT_EQ(plain.locks[1].left_frame_guid, "snake/m1/f1");
  EXPECT_EQ(plain.locks[1].right_frame_guid, "snake/m2/f0");

  o.sensor_after = {0};
  const Robot one = MakeChain(o);
  ASSERT_EQ(one.locks.size(), 3u);
  EXPECT_EQ(one.locks[0].left_frame_guid, "snake/m0/f1");
  EXPECT_EQ(one.locks[0].right_frame_guid, "snake/s0");
  EXPECT_EQ(one.locks[1].left_frame_guid, "snake/s0");
  EXPECT_EQ(one.locks[1].right_frame_guid, "snake/m1/f0");
  EXPECT_EQ(one.locks[2].left_frame_guid, "snake/m1/f1");
}

TEST(ChainBuilder, SensorModulesSitBetweenTheirModules) {
  const Robot r = MakeChain(Sensored(5));
  ASSERT_EQ(r.sensor_modules.size(), 6u);
  ASSERT_EQ(r.locks.size(), 10u);
  for (int k = 0; k < 6; ++k) {
    const SensorModule& sm = r.sensor_modules[k];
    EXPECT_EQ(sm.guid, "cs/s" + std::to_string(k));
    EXPECT_EQ(sm.left_mod_nr, k - 1);
    EXPECT_EQ(sm.right_mod_nr, k == 5 ? -1 : k);
    const double half = sm.size.x() / 2;
    if (k > 0) {  // touches the back of the module in front
      EXPECT_NEAR(r.modules[k - 1].frames[1].position.x() - 0.025,
                  sm.position.x() + half, kEps);
    }
    if (k < 5) {  // and the front of the module behind
      EXPECT_NEAR(r.modules[k].frames[0].position.x() + 0.025,
                  sm.position.x() - half, kEps);
    }
    ASSERT_TRUE(sm.force_sensor.has_value());
    EXPECT_EQ(sm.force_sensor->sensor_position, 0);
    ASSERT_TRUE(sm.force_sensor_lock.has_value());
    EXPECT_EQ(sm.force_sensor_lock->left_frame_guid, sm.guid);
    EXPECT_EQ(sm.force_sensor_lock->right_frame_guid, sm.force_sensor->guid);
    EXPECT_EQ(sm.distance_sensors.size(), k == 0 ? 1u : 0u);
  }
  const SensorModule& front = r.sensor_modules[0];
  EXPECT_GT(front.position.x(), r.modules[0].position.x());
  const DistanceSensor& ray = front.distance_sensors[0];
  EXPECT_EQ(ray.sensor_position, 4);
  EXPECT_EQ(ray.ray_direction, Eigen::Vector3d::UnitX());
  EXPECT_GT(ray.position.x(), front.position.x() + front.size.x() / 2);
  ASSERT_EQ(front.distance_sensor_locks.size(), 1u);
  EXPECT_EQ(front.distance_sensor_locks[0].right_frame_guid, ray.guid);
}

// The cap is a choice, so refusing it says why (REQ-2.4.3).
TEST(ChainBuilder, MoreModulesThanTheCapAreRefusedSayingWhy) {
  ChainOptions o;
  o.modules = kMaxModules + 1;
  try {
    MakeChain(o);
    FAIL() << "1001 modules were built";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("at most 1000, got 1001"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("cube of its joints"),
              std::string::npos)
        << e.what();
  }
}

TEST(ChainBuilder, RejectsBadOptions) {
  ChainOptions o;
  o.modules = 0;
  EXPECT_THROW(MakeChain(o), std::invalid_argument);
  o = ChainOptions();
  o.sensor_after = {11};
  EXPECT_THROW(MakeChain(o), std::invalid_argument);
  o.sensor_after = {2, 2};
  EXPECT_THROW(MakeChain(o), std::invalid_argument);
  o = ChainOptions();
  o.module_mass = 0;
  EXPECT_THROW(MakeChain(o), std::invalid_argument);
  o = ChainOptions();
  o.frame_size.y() = -1;
  EXPECT_THROW(MakeChain(o), std::invalid_argument);
}

TEST(ChainBuilder, AFrontDistanceSensorNeedsASensorModuleInFront) {
  ChainOptions o;
  o.front_distance_sensor = true;
  o.sensor_after = {2, 5};
  try {
    MakeChain(o);
    FAIL() << "a ray facing module 2 was built";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("after module 2 it would face that "
                                    "module and read about 0"));
  }
  o.sensor_after = {};
  EXPECT_THROW(MakeChain(o), std::invalid_argument);
  o.sensor_after = {5, -1};
  const Robot r = MakeChain(o);
  ASSERT_EQ(r.sensor_modules.front().distance_sensors.size(), 1u);
  EXPECT_EQ(r.sensor_modules.front().left_mod_nr, -1);
}

TEST(ChainBuilder, GeneratedChainsPassValidation) {
  for (const ChainOptions& o : {ChainOptions(), Sensored(5), Sensored(1)}) {
    Scenario s;
    s.robots.push_back(MakeChain(o));
    EXPECT_NO_THROW(
        ReadScenarioString(WriteScenarioString(s), "chain.xml", "."));
  }
}

TEST(ChainBuilder, ExampleRobotsAreTheDocumentedChains) {
  ChainOptions snake;
  snake.modules = 11;
  const Scenario s11 =
      ReadScenarioFile(testing::SourcePath("scenarios/snake11.xml"));
  ASSERT_EQ(s11.robots.size(), 1u);
  EXPECT_TRUE(s11.robots[0] == MakeChain(snake));

  ChainOptions cs = Sensored(5);
  cs.name = "case_study";
  const Scenario study =
      ReadScenarioFile(testing::SourcePath("scenarios/case_study.xml"));
  ASSERT_EQ(study.robots.size(), 1u);
  EXPECT_TRUE(study.robots[0] == MakeChain(cs));
  // The ball is ahead in +x, within the front distance sensor's range.
  ASSERT_EQ(study.scene_objects.size(), 1u);
  const SceneObject& ball = study.scene_objects[0];
  EXPECT_EQ(ball.shape, PrimitiveShape::kSphere);
  const DistanceSensor& ray =
      study.robots[0].sensor_modules[0].distance_sensors[0];
  const double gap = ball.position.x() - ball.size.x() / 2 - ray.position.x();
  EXPECT_GT(gap, 0);
  EXPECT_LT(gap, ray.max_ray_distance);
  EXPECT_LT(std::abs(ball.position.z() - ray.position.z()), ball.size.x() / 2);
  // Plastic everywhere, with a plastic/plastic pair.
  EXPECT_EQ(study.scene.material_name, "plastic");
  ASSERT_EQ(study.contact_frictions.size(), 1u);
  EXPECT_EQ(study.contact_frictions[0].material1, "plastic");
  EXPECT_EQ(study.contact_frictions[0].material2, "plastic");
  for (const Module& m : study.robots[0].modules) {
    EXPECT_DOUBLE_EQ(m.frames[0].mass + m.frames[1].mass, 0.1);
    for (const Frame& f : m.frames) EXPECT_EQ(f.material_name, "plastic");
  }
}

}  // namespace
}  // namespace mrsim
