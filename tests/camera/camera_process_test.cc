// mrsim-camera as a real process over LCM on loopback, in lockstep with a
// real mrsim-sim and mrsim-lua: every picture shows a state the simulator
// published (seq and sim time), frames come at the camera's rate, and a
// second run gives the same pictures byte for byte.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "mrsim/camera_image_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

const std::string kCamera = "camera/process/mrsim-camera";
const std::string kLua = "lua_controller/process/mrsim-lua";
const std::string kSim = "sim_core/sim_process/mrsim-sim";

struct Recorder {
  std::map<std::int64_t, robot_state_t> states;
  std::map<std::int64_t, camera_image_t> images;
  int malformed = 0;
  void OnState(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    robot_state_t msg;
    if (DecodeMessage(rbuf, &msg)) states[msg.seq] = msg;
  }
  void OnImage(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    camera_image_t msg;
    if (DecodeMessage(rbuf, &msg)) {
      images[msg.seq] = msg;
    } else {
      ++malformed;
    }
  }
};

void Pump(lcm::LCM& lcm, double seconds, const std::function<bool()>& done) {
  const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end && !done()) HandleFor(lcm, 10);
}

// A yaw snake with a 48x32 head camera at 20 Hz and a red ball ahead.
std::string WriteScenario(const std::string& dir) {
  ChainScenarioOptions options;
  options.chain.name = "eye";
  options.chain.modules = 4;
  options.chain.pattern = ChainPattern::kYaw;
  options.chain.sensor_after = {-1};
  Scenario s = MakeChainScenario(options);
  Camera camera;
  camera.width = 48;
  camera.height = 32;
  camera.rate = 20;
  camera.noise = 3;
  camera.seed = 11;
  s.robots[0].sensor_modules[0].cameras.push_back(camera);
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d::Constant(0.1);
  ball.position =
      s.robots[0].sensor_modules[0].position + Eigen::Vector3d(0.5, 0, 0);
  ball.position.z() = 0.05;
  ball.material_name = "red";
  s.scene_objects.push_back(ball);
  const std::string path = dir + "/eye.xml";
  WriteScenarioFile(s, path);
  return path;
}

// One lockstep run of 1 s: sim, Lua controller and camera.
Recorder RunLockstep(const std::string& dir, const std::string& scenario) {
  const std::string url = TestLcmUrl(8230);
  lcm::LCM lcm(url + "&recv_buf_size=4194304");
  EXPECT_TRUE(lcm.good());
  Recorder rec;
  lcm.subscribe(StateChannel("MRSIM", "eye"), &Recorder::OnState, &rec)
      ->setQueueCapacity(100000);
  lcm.subscribe("MRSIM_CAMERA_eye", &Recorder::OnImage, &rec)
      ->setQueueCapacity(100000);
  ChildProcess camera({BinaryPath(kCamera), "--scenario", scenario, "--lcm-url",
                       url, "--clock", "lockstep", "--exit-with-sim"},
                      dir + "/camera.log");
  ChildProcess lua(
      {BinaryPath(kLua), "--robot", "eye", "--script",
       SourcePath("lua_controller/templates/serpenoid.lua"), "--scenario",
       scenario, "--lcm-url", url, "--exit-with-sim"},
      dir + "/lua.log");
  EXPECT_TRUE(camera.WaitForOutput("listening on", 60)) << camera.Output();
  ChildProcess sim({BinaryPath(kSim), scenario, "--lcm-url", url, "--clock",
                    "lockstep", "--controllers", "mrsim-camera,lua-eye",
                    "--duration", "1", "--lockstep-timeout", "20"},
                   dir + "/sim.log");
  Pump(lcm, 120, [&] { return !sim.running(); });
  EXPECT_EQ(sim.Wait(5), 0) << sim.Output() << camera.Output();
  // 1 s at 20 Hz: frames 0..20.
  Pump(lcm, 20, [&] { return rec.images.size() >= 21; });
  EXPECT_EQ(camera.Wait(30), 0) << camera.Output();
  EXPECT_NE(
      camera.Output().find("pictures published 21, dropped 0, malformed 0"),
      std::string::npos)
      << camera.Output();
  EXPECT_NE(sim.Output().find("answers without targets"), std::string::npos)
      << sim.Output();
  lua.Wait(30);
  return rec;
}

TEST(CameraProcess, LockstepPicturesShowPublishedStatesTheSameOnARerun) {
  const std::string dir = TempDir("camera_process_lockstep");
  const std::string scenario = WriteScenario(dir);
  const Recorder first = RunLockstep(dir, scenario);
  ASSERT_EQ(first.images.size(), 21u);
  EXPECT_EQ(first.malformed, 0);
  for (const auto& [seq, image] : first.images) {
    const auto state = first.states.find(seq);
    ASSERT_NE(state, first.states.end()) << "no state with seq " << seq;
    EXPECT_EQ(image.sim_time, state->second.sim_time);
    EXPECT_EQ(image.width, 48);
    EXPECT_EQ(image.height, 32);
    EXPECT_EQ(image.encoding, "rgb8");
    EXPECT_EQ(image.sender, "mrsim-camera");
  }
  // Frame k at the first state at or after k / 20 s: every fifth state.
  EXPECT_EQ(first.images.begin()->first, 0);
  EXPECT_EQ(first.images.rbegin()->first, 100);

  const Recorder again = RunLockstep(dir, scenario);
  ASSERT_EQ(again.images.size(), first.images.size());
  for (const auto& [seq, image] : first.images) {
    const auto other = again.images.find(seq);
    ASSERT_NE(other, again.images.end()) << seq;
    EXPECT_EQ(other->second.data, image.data) << "picture of seq " << seq;
  }
}

}  // namespace
}  // namespace mrsim
