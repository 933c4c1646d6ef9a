// Scene objects in the viewer: movable objects take the pose of the newest
// scene state at or before a frame's time (scene_state_t on <prefix>_SCENE,
// live or from a log); without one they stay where the scenario puts them.
#include <gtest/gtest.h>

#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <string>
#include <vector>

#include "lcmtypes/runtime/channels.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/physics/scene_object_state.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/viewer/viewer_test_util.h"
#include "viewer/frame_scheduler.h"
#include "viewer/frame_writer.h"
#include "viewer/gl_context.h"
#include "viewer/process/state_inbox.h"
#include "viewer/state_viewer.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::TempDir;
using testing::TestLcmUrl;

constexpr int kBall = 1;  // index in scene_objects (0 is the static box)

// The viewer test snake and box, plus a movable ball beside the snake.
Scenario BallScenario() {
  Scenario s = testing::ViewerTestScenario();
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.1, 0.1, 0.1);
  ball.position = Eigen::Vector3d(0.15, -0.25, 0.05);
  ball.mass = 0.05;
  s.scene_objects.push_back(ball);
  return s;
}

std::vector<SceneObjectState> BallAt(const Eigen::Vector3d& p) {
  SceneObjectState s;
  s.index = kBall;
  s.pose.position = p;
  s.pose.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()));
  return {s};
}

int BallBody(const mjModel* m) {
  return mj_name2id(m, mjOBJ_BODY, mjcf_names::SceneObject(kBall).c_str());
}

TEST(ViewerScene, BallBodyTakesTheScenePoseAndTheFrameShowsIt) {
  GlContext gl;
  const Scenario scenario = BallScenario();
  Physics physics(scenario);
  const RobotState state = physics.ReadRobotState(0);
  StateViewer viewer(scenario, testing::FixedView());
  const int ball = BallBody(viewer.model());
  ASSERT_GT(ball, 0);

  cv::Mat built;
  viewer.Render({&state}, &built);  // no scene state: the scenario pose
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(viewer.data()->xpos[3 * ball + k],
                scenario.scene_objects[kBall].position[k], 1e-12);
  }

  const std::vector<SceneObjectState> moved =
      BallAt(Eigen::Vector3d(0.15, 0.25, 0.05));
  cv::Mat image;
  viewer.Render({&state}, &image, &moved);
  const mjtNum* xpos = viewer.data()->xpos + 3 * ball;
  const mjtNum* xquat = viewer.data()->xquat + 4 * ball;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(xpos[k], moved[0].pose.position[k], 1e-12);
  }
  const Eigen::Quaterniond& q = moved[0].pose.orientation;
  EXPECT_NEAR(xquat[0], q.w(), 1e-12);
  EXPECT_NEAR(xquat[1], q.x(), 1e-12);
  EXPECT_NEAR(xquat[2], q.y(), 1e-12);
  EXPECT_NEAR(xquat[3], q.z(), 1e-12);
  // The ball's geom follows its body.
  const int geom = mj_name2id(viewer.model(), mjOBJ_GEOM,
                              mjcf_names::SceneObject(kBall).c_str());
  ASSERT_GE(geom, 0);
  EXPECT_NEAR(viewer.data()->geom_xpos[3 * geom + 1], 0.25, 1e-12);

  // The picture changes where the ball was and where it went, and nowhere
  // else: the rest of the frame is the same.
  cv::Mat diff;
  cv::absdiff(built, image, diff);
  cv::Mat grey;
  cv::cvtColor(diff, grey, cv::COLOR_BGR2GRAY);
  const cv::Rect changed = cv::boundingRect(grey > 30);
  EXPECT_GT(testing::MeanAbsDiff(built, image), 0.5);
  EXPECT_GT(changed.area(), 100);
  EXPECT_LT(changed.area(), built.cols * built.rows / 2);

  // Back at the scenario pose through a scene state: the same picture.
  cv::Mat back;
  std::vector<SceneObjectState> upright =
      BallAt(scenario.scene_objects[kBall].position);
  upright[0].pose.orientation = Eigen::Quaterniond::Identity();
  viewer.Render({&state}, &back, &upright);
  EXPECT_LT(testing::MeanAbsDiff(built, back), 0.05);
}

// A misspelled --robot lists the robots there are.
TEST(ViewerScene, AnUnknownRobotToFollowNamesTheRobots) {
  GlContext gl;
  ViewerOptions options = testing::FixedView();
  options.follow_robot = "snek";
  const Scenario scenario = BallScenario();
  try {
    StateViewer viewer(scenario, options);
    FAIL() << "followed a robot that is not there";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "--robot 'snek' is not a robot of the scenario (it has " +
                  scenario.robots[0].name + ")"),
              std::string::npos)
        << e.what();
  }
}

TEST(ViewerScene, SchedulerShowsTheNewestSceneAtOrBeforeEachFrame) {
  FrameScheduler scheduler(10.0, 1);  // frames every 100 ms
  FrameScheduler::Frame frame;
  RobotState state;
  ASSERT_TRUE(scheduler.Push(0, 0, state));
  ASSERT_TRUE(scheduler.NextFrame(&frame));
  EXPECT_EQ(frame.scene, nullptr);  // none yet: objects as built
  EXPECT_EQ(frame.scene_key, -1);

  for (int64_t u = 30000; u <= 330000; u += 30000) {
    ASSERT_TRUE(scheduler.PushScene(
        u, BallAt(Eigen::Vector3d(static_cast<double>(u), 0, 0))));
    ASSERT_TRUE(scheduler.Push(0, u, state));
  }
  EXPECT_FALSE(scheduler.PushScene(320000, {}));  // older: dropped
  std::vector<int64_t> keys;
  while (scheduler.NextFrame(&frame)) {
    ASSERT_NE(frame.scene, nullptr);
    EXPECT_EQ(frame.scene->at(0).pose.position.x(),
              static_cast<double>(frame.scene_key));
    keys.push_back(frame.scene_key);
  }
  EXPECT_EQ(keys, (std::vector<int64_t>{90000, 180000, 300000}));

  // A reset: the scene of the new run (sent before its robot state) shows.
  ASSERT_TRUE(scheduler.PushScene(0, BallAt(Eigen::Vector3d(-1, 0, 0))));
  ASSERT_TRUE(scheduler.Push(0, 0, state));
  ASSERT_TRUE(scheduler.NextFrame(&frame));
  EXPECT_EQ(frame.index, 0);
  ASSERT_NE(frame.scene, nullptr);
  EXPECT_EQ(frame.scene_key, 0);
  EXPECT_EQ(frame.scene->at(0).pose.position.x(), -1.0);
}

std::vector<unsigned char> Bytes(const scene_state_t& msg) {
  std::vector<unsigned char> bytes(msg.getEncodedSize());
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

TEST(ViewerScene, InboxCountsAndDropsMalformedSceneStates) {
  GlContext gl;
  ViewerOptions options;
  options.width = 64;
  options.height = 48;
  StateViewer viewer(BallScenario(), options);
  FrameScheduler scheduler(10.0, viewer.robot_count());
  StateInbox inbox(viewer, "MRSIM", &scheduler);
  const std::string channel = SceneChannel("MRSIM");
  EXPECT_EQ(inbox.scene_channel(), "MRSIM_SCENE");
  auto send = [&](std::vector<SceneObjectState> objects, int64_t seq) {
    const std::vector<unsigned char> b =
        Bytes(ToSceneStateMessage(objects, seq * 0.01, seq));
    return inbox.Receive(channel, b.data(), static_cast<int>(b.size()));
  };
  const unsigned char junk[] = {7, 7, 7};
  EXPECT_FALSE(inbox.Receive(channel, junk, sizeof(junk)));
  std::vector<SceneObjectState> s = BallAt(Eigen::Vector3d(0, 0, 0.05));
  s[0].index = 0;  // the static box
  EXPECT_FALSE(send(s, 1));
  s[0].index = 5;  // no such object
  EXPECT_FALSE(send(s, 2));
  s[0].index = kBall;
  s[0].pose.position.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(send(s, 3));
  std::vector<SceneObjectState> twice = BallAt(Eigen::Vector3d(0, 0, 0.05));
  twice.push_back(twice[0]);
  EXPECT_FALSE(send(twice, 4));
  EXPECT_EQ(inbox.malformed(), 5);
  EXPECT_EQ(inbox.scenes(), 0);

  EXPECT_TRUE(send(BallAt(Eigen::Vector3d(0, 0, 0.05)), 5));
  EXPECT_EQ(inbox.scenes(), 1);
  EXPECT_EQ(inbox.accepted(), 0);  // robot states only
}

// mrsim-view live: scene states on MRSIM_SCENE move the ball in the frames
// it writes, exactly as the same viewer renders them in process.
TEST(ViewerScene, LiveViewerDrawsTheBallWhereSceneStatesPutIt) {
  const std::string dir = TempDir("viewer_scene_live");
  const std::string frames_dir = dir + "/frames";
  const std::string url = TestLcmUrl(7861);
  const Scenario scenario = BallScenario();
  const std::string scenario_path = testing::WriteTestScenario(scenario, dir);
  std::vector<std::string> args = {BinaryPath("viewer/process/mrsim-view"),
                                   scenario_path,
                                   "--lcm-url",
                                   url,
                                   "--frames-dir",
                                   frames_dir,
                                   "--fps",
                                   "10",
                                   "--no-overlay",
                                   "--max-frames",
                                   "2"};
  for (const std::string& f : testing::FixedViewFlags()) args.push_back(f);
  ChildProcess view(args, dir + "/viewer.log");
  ASSERT_TRUE(view.WaitForOutput("listening", 30.0)) << view.Output();

  GlContext gl;
  StateViewer expected_viewer(ReadScenarioFile(scenario_path),
                              testing::FixedView());
  Physics physics(ReadScenarioFile(scenario_path));
  const RobotState s0 = physics.ReadRobotState(0);
  testing::DriveTo(&physics, 0.1);
  const RobotState s1 = physics.ReadRobotState(0);
  const std::vector<SceneObjectState> b0 =
      BallAt(Eigen::Vector3d(0.15, -0.25, 0.05));
  const std::vector<SceneObjectState> b1 =
      BallAt(Eigen::Vector3d(0.2, 0.25, 0.05));
  std::vector<cv::Mat> expected(2);
  expected_viewer.Render({&s0}, &expected[0], &b0);
  expected_viewer.Render({&s1}, &expected[1], &b1);

  lcm::LCM lcm(url);
  ASSERT_TRUE(lcm.good());
  const std::string state_channel = StateChannel("MRSIM", "snake");
  // As mrsim-sim does: the scene of a period before its robot states.
  const scene_state_t scene0 = ToSceneStateMessage(b0, s0.time, 0);
  const robot_state_t state0 = ToRobotStateMessage(s0, 0);
  lcm.publish(SceneChannel("MRSIM"), &scene0);
  lcm.publish(state_channel, &state0);
  // The viewer keeps a history of both streams: no pacing needed. Repeated
  // until it has its two frames and stops.
  const scene_state_t scene1 = ToSceneStateMessage(b1, s1.time, 1);
  const robot_state_t state1 = ToRobotStateMessage(s1, 1);
  int code = -1;
  testing::RepeatUntil(
      [&] {
        lcm.publish(SceneChannel("MRSIM"), &scene1);
        lcm.publish(state_channel, &state1);
      },
      [&] { return (code = view.Wait(0)) != -1; }, 0.1, 30.0);
  ASSERT_EQ(code, 0) << view.Output();
  // The test repeats the last scene until the viewer stops, so a loaded
  // machine may deliver more than two before it does.
  std::smatch scenes;
  const std::string output = view.Output();
  ASSERT_TRUE(
      std::regex_search(output, scenes, std::regex("(\\d+) scene states")))
      << output;
  EXPECT_GE(std::stoi(scenes[1]), 2) << output;
  for (int k = 0; k < 2; ++k) {
    const std::string file = FrameWriter::PngName(frames_dir, k);
    const cv::Mat frame = cv::imread(file);
    ASSERT_FALSE(frame.empty()) << file << "\n" << view.Output();
    cv::imwrite(dir + "/expected_" + std::to_string(k) + ".png", expected[k]);
    EXPECT_LT(testing::MeanAbsDiff(frame, expected[k]), 0.5) << file;
  }
  // Without the scene state the ball would be elsewhere: the check bites.
  cv::Mat unmoved;
  expected_viewer.Render({&s1}, &unmoved);
  EXPECT_GT(testing::MeanAbsDiff(unmoved, expected[1]), 0.5);
}

}  // namespace
}  // namespace mrsim
