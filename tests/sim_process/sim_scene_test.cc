// Scene objects on the wire: mrsim-sim publishes the movable scene objects'
// poses (scene_state_t on <prefix>_SCENE) exactly as the physics has them.
#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "mrsim/scene_state_t.hpp"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/physics/scene_object_state.h"
#include "tests/common/child_process.h"
#include "tests/sim_process/sim_client.h"

namespace mrsim::testing {
namespace {

// A 3-module snake, a static box (object 0) and a ball (object 1) dropped
// from 0.3 m so it moves without any command.
Scenario BallScenario() {
  Scenario s;
  ChainOptions chain;
  chain.name = "snake";
  chain.modules = 3;
  s.robots.push_back(MakeChain(chain));
  SceneObject box;
  box.guid = "box";
  box.position = Eigen::Vector3d(0.0, 0.6, 0.05);
  box.is_static = true;
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.08, 0.08, 0.08);
  ball.position = Eigen::Vector3d(0.5, 0.0, 0.3);
  ball.mass = 0.05;
  s.scene_objects = {box, ball};
  return s;
}

void ExpectPoseOfBody(const Physics& physics, int object, const Pose& pose) {
  const int body = mj_name2id(physics.model(), mjOBJ_BODY,
                              mjcf_names::SceneObject(object).c_str());
  ASSERT_GT(body, 0);
  const mjtNum* p = physics.data()->xpos + 3 * body;
  const mjtNum* q = physics.data()->xquat + 4 * body;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(pose.position[k], p[k]);
  EXPECT_EQ(pose.orientation.w(), q[0]);
  EXPECT_EQ(pose.orientation.x(), q[1]);
  EXPECT_EQ(pose.orientation.y(), q[2]);
  EXPECT_EQ(pose.orientation.z(), q[3]);
}

TEST(SimProcessScene, MessageCarriesThePhysicsPoseOfEachMovableObject) {
  Physics physics(BallScenario());
  physics.Step(100);
  const std::vector<SceneObjectState> objects = ReadSceneObjects(physics);
  ASSERT_EQ(objects.size(), 1u);  // the static box is not listed
  EXPECT_EQ(objects[0].index, 1);
  ExpectPoseOfBody(physics, 1, objects[0].pose);
  EXPECT_LT(objects[0].pose.position.z(), 0.29);  // it fell

  const scene_state_t msg = ToSceneStateMessage(objects, physics.time(), 7);
  EXPECT_EQ(msg.seq, 7);
  EXPECT_EQ(msg.utime, SimTimeToUtime(physics.time()));
  EXPECT_EQ(msg.sim_time, physics.time());
  ASSERT_EQ(msg.num_objects, 1);
  EXPECT_EQ(msg.object_index[0], 1);
  ExpectPoseOfBody(physics, 1, FromSceneStateMessage(msg)[0].pose);

  scene_state_t bad = msg;
  bad.num_objects = 2;
  EXPECT_THROW(FromSceneStateMessage(bad), std::invalid_argument);
}

TEST(SimProcessScene, NothingToReadWithoutMovableObjects) {
  Scenario s = BallScenario();
  s.scene_objects.pop_back();
  Physics physics(s);
  physics.Step(10);
  EXPECT_TRUE(ReadSceneObjects(physics).empty());
}

struct SceneListener {
  void On(const lcm::ReceiveBuffer*, const std::string&,
          const scene_state_t* msg) {
    last = *msg;
    ++received;
  }
  scene_state_t last{};
  int received = 0;
};

TEST(SimProcessScene, SimPublishesSceneStatesWithTheRobotStatesSeq) {
  const std::string dir = TempDir("sim_scene");
  const std::string scenario = dir + "/ball.xml";
  WriteScenarioFile(BallScenario(), scenario);
  const int port = 7860;
  SimClient client(TestLcmUrl(port));
  SceneListener scene;
  client.lcm().subscribe(SceneChannel(kDefaultChannelPrefix),
                         &SceneListener::On, &scene);
  ChildProcess sim({SimBinary(), scenario, "--lcm-url", TestLcmUrl(port),
                    "--rate", "100", "--clock", "fast", "--paused"},
                   dir + "/sim.log");
  ASSERT_TRUE(client.WaitFor(
      [&] { return client.states_received() > 0 && client.status(); }, 10))
      << sim.Output();
  ASSERT_TRUE(client.StepAndWait(20)) << sim.Output();
  // The scene of a period is sent just before its robot states.
  ASSERT_GT(scene.received, 0) << sim.Output();
  EXPECT_EQ(scene.last.seq, 20);
  EXPECT_EQ(scene.last.seq, client.states().at("snake").seq);
  EXPECT_EQ(scene.last.utime, client.states().at("snake").utime);

  // The same 20 periods without commands, in process: the same ball pose.
  Physics physics(ReadScenarioFile(scenario));
  const int steps =
      static_cast<int>(std::lround(1.0 / (100.0 * physics.timestep())));
  physics.Step(20 * steps);
  ASSERT_EQ(scene.last.num_objects, 1);
  EXPECT_EQ(scene.last.object_index[0], 1);
  EXPECT_EQ(scene.last.sim_time, physics.time());
  ExpectPoseOfBody(physics, 1, FromSceneStateMessage(scene.last)[0].pose);
  EXPECT_EQ(sim.Stop(5.0), 0);
}

}  // namespace
}  // namespace mrsim::testing
