// In-process tests of the viewer library: off-screen rendering, the state to
// pose mapping against the physics' own pose, rays, camera and scheduling.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "tests/common/child_process.h"
#include "tests/viewer/viewer_test_util.h"
#include "viewer/camera_control.h"
#include "viewer/frame_scheduler.h"
#include "viewer/gl_context.h"
#include "viewer/renderer.h"
#include "viewer/state_viewer.h"

namespace mrsim {
namespace {

using testing::DriveTo;
using testing::GreyStdDev;
using testing::MeanAbsDiff;
using testing::PhysicsRays;
using testing::ViewerTestScenario;

constexpr int kWidth = 320;
constexpr int kHeight = 240;

ViewerOptions FixedView() {
  ViewerOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.camera.mode = CameraMode::kFixed;
  options.camera.lookat = Eigen::Vector3d(0.1, 0.0, 0.05);
  options.camera.distance = 0.9;
  options.camera.azimuth = 120;
  options.camera.elevation = -30;
  options.gait = "test wave";
  return options;
}

TEST(ViewerRender, OffscreenFrameOfTheScenarioIsNotBlank) {
  GlContext gl;
  EXPECT_NE(gl.description().find("EGL"), std::string::npos);
  StateViewer viewer(ViewerTestScenario(), FixedView());
  cv::Mat image;
  viewer.Render({nullptr}, &image);
  ASSERT_EQ(image.cols, kWidth);
  ASSERT_EQ(image.rows, kHeight);
  EXPECT_GT(GreyStdDev(image), 10.0);
}

TEST(ViewerRender, FrameFromStateMatchesPhysicsRenderedDirectly) {
  GlContext gl;
  const Scenario scenario = ViewerTestScenario();
  Physics physics(scenario);
  DriveTo(&physics, 0.7);
  const RobotState state = physics.ReadRobotState(0);

  const ViewerOptions options = FixedView();
  StateViewer viewer(scenario, options);
  cv::Mat from_state;
  viewer.Render({&state}, &from_state);

  // The truth: the physics' own mjData, same camera, rays from its sites.
  Renderer renderer(physics.model(), kWidth, kHeight);
  CameraControl camera(options.camera);
  Overlay overlay;
  overlay.time = state.time;
  overlay.speed = state.com_velocity.norm();
  overlay.gait = options.gait;
  cv::Mat direct;
  renderer.Render(physics.mutable_data(), camera.camera(),
                  PhysicsRays(physics, state), &overlay, &direct);

  const std::string dir = testing::TempDir("viewer_render_match");
  cv::imwrite(dir + "/from_state.png", from_state);
  cv::imwrite(dir + "/direct.png", direct);
  EXPECT_LT(MeanAbsDiff(from_state, direct), 0.5)
      << "see " << dir << "/from_state.png and direct.png";

  // And the robot did move away from where it was built.
  cv::Mat built;
  viewer.Render({nullptr}, &built);
  EXPECT_GT(MeanAbsDiff(from_state, built), 0.5);
}

TEST(ViewerRender, EveryRobotTakesItsOwnState) {
  GlContext gl;
  Scenario scenario = ViewerTestScenario();
  ChainOptions second;
  second.name = "worm";
  second.modules = 3;
  second.origin = Eigen::Vector3d(-0.1, 0.3, 0.0);
  scenario.robots.push_back(MakeChain(second));
  Physics physics(scenario);
  DriveTo(&physics, 0.5);
  const RobotState a = physics.ReadRobotState(0);
  const RobotState b = physics.ReadRobotState(1);

  ViewerOptions options = FixedView();
  options.overlay = false;
  options.rays = false;
  options.camera.lookat = Eigen::Vector3d(0.0, 0.15, 0.05);
  StateViewer viewer(scenario, options);
  ASSERT_EQ(viewer.robot_count(), 2);
  EXPECT_EQ(viewer.robot_index("worm"), 1);
  cv::Mat from_states;
  viewer.Render({&a, &b}, &from_states);

  Renderer renderer(physics.model(), kWidth, kHeight);
  CameraControl camera(options.camera);
  cv::Mat direct;
  renderer.Render(physics.mutable_data(), camera.camera(), {}, nullptr,
                  &direct);
  EXPECT_LT(MeanAbsDiff(from_states, direct), 0.5);
  // Robot "worm" without a state stays as built: a different picture.
  cv::Mat one_missing;
  viewer.Render({&a, nullptr}, &one_missing);
  EXPECT_GT(MeanAbsDiff(one_missing, direct), 0.01);
}

TEST(ViewerRender, DistanceRaysAreDrawnWithTheMeasuredLength) {
  GlContext gl;
  const Scenario scenario = ViewerTestScenario();
  Physics physics(scenario);
  physics.Step();
  RobotState state = physics.ReadRobotState(0);
  ASSERT_EQ(state.sensor_modules.size(), 1u);
  ASSERT_EQ(state.sensor_modules[0].distances.size(), 1u);

  ViewerOptions options = FixedView();
  options.overlay = false;
  StateViewer with_rays(scenario, options);
  options.rays = false;
  StateViewer without_rays(scenario, options);
  cv::Mat a, b, shorter;
  with_rays.Render({&state}, &a);
  without_rays.Render({&state}, &b);
  EXPECT_GT(MeanAbsDiff(a, b), 0.01);
  // A shorter reading draws less ray.
  state.sensor_modules[0].distances[0] *= 0.3;
  with_rays.Render({&state}, &shorter);
  EXPECT_GT(MeanAbsDiff(a, shorter), 0.005);
}

TEST(ViewerRender, TerrainHeightFieldIsDrawn) {
  GlContext gl;
  const std::string dir = testing::TempDir("viewer_terrain");
  cv::Mat hills(32, 32, CV_8UC1);
  for (int r = 0; r < hills.rows; ++r) {
    for (int c = 0; c < hills.cols; ++c) {
      hills.at<unsigned char>(r, c) = static_cast<unsigned char>(
          127 + 120 * std::sin(r * 0.4) * std::cos(c * 0.4));
    }
  }
  ASSERT_TRUE(cv::imwrite(dir + "/hills.png", hills));
  Scenario flat = ViewerTestScenario();
  Scenario hilly = flat;
  hilly.scene.height_image = dir + "/hills.png";
  hilly.scene.height = 0.3;
  hilly.scene.meters_per_pixel = 0.1;
  hilly.scene.position = Eigen::Vector3d(-1.6, -1.6, -0.3);
  ViewerOptions options = FixedView();
  options.overlay = false;
  cv::Mat a, b;
  StateViewer(flat, options).Render({nullptr}, &a);
  StateViewer(hilly, options).Render({nullptr}, &b);
  EXPECT_GT(MeanAbsDiff(a, b), 2.0);
  cv::imwrite(dir + "/hilly.png", b);
}

TEST(ViewerRender, FollowCameraTracksTheCentreOfMass) {
  GlContext gl;
  const Scenario scenario = ViewerTestScenario();
  ViewerOptions options = FixedView();
  options.camera.mode = CameraMode::kFollow;
  options.camera.lookat = Eigen::Vector3d::Zero();
  options.overlay = false;
  options.rays = false;
  StateViewer viewer(scenario, options);
  Physics physics(scenario);
  physics.Step();
  RobotState state = physics.ReadRobotState(0);
  cv::Mat here, moved;
  viewer.Render({&state}, &here);
  // The whole robot shifted 1 m sideways: the camera goes with it.
  for (auto& f : state.frames) f.position.y() += 1.0;
  for (auto& sm : state.sensor_modules) sm.pose.position.y() += 1.0;
  state.com.y() += 1.0;
  viewer.Render({&state}, &moved);
  const Eigen::Vector3d lookat = viewer.camera()->lookat();
  EXPECT_NEAR(lookat.y(), state.com.y(), 1e-9);
  EXPECT_NEAR(lookat.x(), state.com.x(), 1e-9);
  EXPECT_GT(MeanAbsDiff(here, moved), 0.1);  // the box and ground moved
}

TEST(ViewerCamera, OrbitPanZoomAndReset) {
  CameraSettings settings;
  settings.mode = CameraMode::kFixed;
  settings.lookat = Eigen::Vector3d(1, 2, 3);
  settings.distance = 2.0;
  settings.azimuth = 90;
  settings.elevation = -20;
  CameraControl cam(settings);
  cam.Orbit(10, -100);  // elevation clamps
  EXPECT_DOUBLE_EQ(cam.camera().azimuth, 100);
  EXPECT_DOUBLE_EQ(cam.camera().elevation, -89);
  cam.Zoom(0.5);
  EXPECT_DOUBLE_EQ(cam.camera().distance, 1.0);
  cam.Reset();
  cam.Pan(0.5, 0.0);  // azimuth 90: looking along +y, right is +x
  EXPECT_NEAR(cam.lookat().x(), 1.0 + 1.0, 1e-9);
  EXPECT_NEAR(cam.lookat().y(), 2.0, 1e-9);
  cam.Track(Eigen::Vector3d(10, 10, 10));  // fixed: ignored
  EXPECT_NEAR(cam.lookat().y(), 2.0, 1e-9);
  cam.ToggleMode();  // follow, view kept
  EXPECT_NEAR(cam.lookat().x(), 2.0, 1e-9);
  cam.Track(Eigen::Vector3d(11, 10, 10));
  EXPECT_NEAR(cam.lookat().x(), 3.0, 1e-9);
}

RobotState StateAt(double t) {
  RobotState s;
  s.time = t;
  return s;
}

TEST(ViewerFrameScheduler, FramesAtFixedSimTimeShowNewestStateAtOrBefore) {
  FrameScheduler scheduler(10.0, 1);  // frames every 100 ms
  FrameScheduler::Frame frame;
  // States every 30 ms from 0 to 330 ms.
  std::vector<int64_t> shown;
  std::vector<int64_t> indices;
  for (int64_t u = 0; u <= 330000; u += 30000) {
    ASSERT_TRUE(scheduler.Push(0, u, StateAt(u * 1e-6)));
    while (scheduler.NextFrame(&frame)) {
      indices.push_back(frame.index);
      shown.push_back(frame.key[0]);
    }
  }
  EXPECT_EQ(indices, (std::vector<int64_t>{0, 1, 2, 3}));
  EXPECT_EQ(shown, (std::vector<int64_t>{0, 90000, 180000, 300000}));
}

TEST(ViewerFrameScheduler, LateStartBeginsAtFirstFrameAfterFirstState) {
  FrameScheduler scheduler(30.0, 1);
  FrameScheduler::Frame frame;
  scheduler.Push(0, 5010000, StateAt(5.01));
  EXPECT_FALSE(scheduler.NextFrame(&frame));  // frame 151 is at 5.0333 s
  scheduler.Push(0, 5040000, StateAt(5.04));
  ASSERT_TRUE(scheduler.NextFrame(&frame));
  EXPECT_EQ(frame.index, 151);
  EXPECT_EQ(frame.key[0], 5010000);
  EXPECT_FALSE(scheduler.NextFrame(&frame));
}

TEST(ViewerFrameScheduler, LostStatesRepeatTheNewestAndOldOnesAreDropped) {
  FrameScheduler scheduler(10.0, 2);
  FrameScheduler::Frame frame;
  scheduler.Push(0, 0, StateAt(0));
  ASSERT_TRUE(scheduler.NextFrame(&frame));
  EXPECT_EQ(frame.key, (std::vector<int64_t>{0, -1}));  // robot 1 not seen
  scheduler.Push(1, 50000, StateAt(0.05));
  // A jump of 3 frames: frames 1..3 all show the newest state before them.
  scheduler.Push(0, 350000, StateAt(0.35));
  std::vector<std::vector<int64_t>> keys;
  while (scheduler.NextFrame(&frame)) keys.push_back(frame.key);
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_EQ(keys[0], (std::vector<int64_t>{0, 50000}));
  EXPECT_EQ(keys[2], (std::vector<int64_t>{0, 50000}));
  EXPECT_FALSE(scheduler.Push(0, 340000, StateAt(0.34)));  // out of order
}

TEST(ViewerFrameScheduler, BusyViewerKeepsTheNewestStatesOnly) {
  FrameScheduler scheduler(10.0, 1, 3);  // keeps 3 states per robot
  FrameScheduler::Frame frame;
  scheduler.Push(0, 0, StateAt(0));
  ASSERT_TRUE(scheduler.NextFrame(&frame));
  // While a frame renders, a whole second of states arrives.
  for (int64_t u = 100000; u <= 1000000; u += 100000) {
    scheduler.Push(0, u, StateAt(u * 1e-6));
  }
  std::vector<int64_t> shown;
  while (scheduler.NextFrame(&frame)) shown.push_back(frame.key[0]);
  // Frames 1..10 are all written; the dropped states' frames repeat the
  // oldest kept one, then the newest are shown.
  ASSERT_EQ(shown.size(), 10u);
  EXPECT_EQ(shown.front(), 800000);
  EXPECT_EQ(shown[8], 900000);
  EXPECT_EQ(shown.back(), 1000000);
}

// A recording viewer that renders slower than the simulation runs: the
// states arrive long before their frames render, yet every frame shows the
// state of its own time (the demo video once ran ahead, then froze).
TEST(ViewerFrameScheduler, SlowViewerStillShowsEachFrameItsOwnState) {
  FrameScheduler scheduler(30.0, 1, 64);  // 64 frames may wait
  FrameScheduler::Frame frame;
  // Two seconds of 100 Hz states (200 of them, more than 64) before any
  // frame renders.
  for (int64_t u = 0; u <= 2000000; u += 10000) {
    ASSERT_TRUE(scheduler.Push(0, u, StateAt(u * 1e-6)));
  }
  std::vector<int64_t> shown;
  while (scheduler.NextFrame(&frame)) {
    // The newest 10 ms state at or before k / 30 s.
    const int64_t t = scheduler.FrameUtime(frame.index);
    EXPECT_EQ(frame.key[0], t / 10000 * 10000) << frame.index;
    shown.push_back(frame.key[0]);
  }
  ASSERT_EQ(shown.size(), 61u);  // frames 0..60
  EXPECT_EQ(shown.back(), 2000000);
}

TEST(ViewerFrameScheduler, SimulatorResetRestartsTheSchedule) {
  FrameScheduler scheduler(10.0, 1);
  FrameScheduler::Frame frame;
  scheduler.Push(0, 1000000, StateAt(1.0));
  while (scheduler.NextFrame(&frame)) {
  }
  scheduler.Push(0, 0, StateAt(0.0));
  ASSERT_TRUE(scheduler.NextFrame(&frame));
  EXPECT_EQ(frame.index, 0);
  EXPECT_EQ(scheduler.restarts(), 1);
}

}  // namespace
}  // namespace mrsim
