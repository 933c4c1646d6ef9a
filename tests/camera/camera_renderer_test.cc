// What a robot's camera sees, rendered for real (EGL, Mesa's llvmpipe, no
// display) from the physics' own poses: a red ball ahead is red in the
// middle of the picture, to the side once the robot has turned, and the
// same picture comes out bit for bit for the same state. Cameras on scene
// objects and loose sensor modules render the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"
#include "viewer/camera_image_renderer.h"
#include "viewer/gl_context.h"

namespace mrsim {
namespace {

// A yaw snake with a camera on the front face of a sensor module in front
// of module 0, and a red ball `ahead` m in front of it on the ground.
Scenario RedBallAhead(double ahead, double noise = 0) {
  ChainScenarioOptions options;
  options.chain.name = "eye";
  options.chain.modules = 3;
  options.chain.pattern = ChainPattern::kYaw;
  options.chain.sensor_after = {-1};
  Scenario s = MakeChainScenario(options);
  Camera camera;
  camera.sensor_position = 4;
  camera.width = 80;
  camera.height = 60;
  camera.noise = noise;
  camera.seed = 7;
  s.robots[0].sensor_modules[0].cameras.push_back(camera);
  const SensorModule& head = s.robots[0].sensor_modules[0];
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d::Constant(0.1);
  ball.position =
      head.position + Eigen::Vector3d(ahead, 0, 0.05 - head.position.z());
  ball.is_static = true;
  ball.material_name = "red";
  s.scene_objects.push_back(ball);
  return s;
}

// Fraction of pixels in columns [x0, x1) that are clearly red.
double RedShare(const std::vector<std::uint8_t>& rgb, int width, int height,
                int x0, int x1) {
  int red = 0, all = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
      red += p[0] > 120 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
      ++all;
    }
  }
  return static_cast<double>(red) / all;
}

TEST(CameraRenderer, ARedBallAheadIsRedInTheMiddleOfThePicture) {
  GlContext gl;
  const Scenario s = RedBallAhead(0.4);
  Physics physics(s);
  CameraImageRenderer renderer(physics.model(), s);
  ASSERT_EQ(renderer.cameras().size(), 1u);
  EXPECT_EQ(renderer.cameras()[0].name, "eye/sm0/camera");
  std::vector<std::uint8_t> rgb;
  renderer.Render(0, physics.mutable_data(), 0, &rgb);
  ASSERT_EQ(rgb.size(), 80u * 60 * 3);
  EXPECT_GT(RedShare(rgb, 80, 60, 30, 50), 0.1);
  EXPECT_LT(RedShare(rgb, 80, 60, 0, 15), 0.01);
  EXPECT_LT(RedShare(rgb, 80, 60, 65, 80), 0.01);
}

TEST(CameraRenderer, TheBallMovesToTheSideOfThePictureWhenTheRobotTurns) {
  GlContext gl;
  Scenario s = RedBallAhead(0.4);
  // The robot turned left by 20 degrees about its head: the ball, still
  // dead ahead of where it looked, is now right of the picture's centre.
  const double yaw = 20 * M_PI / 180;
  const Eigen::Vector3d pivot = s.robots[0].sensor_modules[0].position;
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  for (Module& m : s.robots[0].modules) {
    m.position = pivot + turn * (m.position - pivot);
    for (Frame& f : m.frames) {
      f.position = pivot + turn * (f.position - pivot);
      f.quat_rotation = turn * f.quat_rotation;
    }
  }
  for (SensorModule& sm : s.robots[0].sensor_modules) {
    sm.position = pivot + turn * (sm.position - pivot);
    sm.quat_rotation = turn * sm.quat_rotation;
  }
  Physics physics(s);
  CameraImageRenderer renderer(physics.model(), s);
  std::vector<std::uint8_t> rgb;
  renderer.Render(0, physics.mutable_data(), 0, &rgb);
  EXPECT_LT(RedShare(rgb, 80, 60, 30, 40), 0.01);
  EXPECT_GT(RedShare(rgb, 80, 60, 50, 80), 0.05);
}

TEST(CameraRenderer, TheSameStateGivesTheSamePictureBitForBit) {
  GlContext gl;
  const Scenario s = RedBallAhead(0.4, /*noise=*/8);
  Physics physics(s);
  std::vector<std::uint8_t> first, again, later;
  {
    CameraImageRenderer renderer(physics.model(), s);
    renderer.Render(0, physics.mutable_data(), 5, &first);
  }
  CameraImageRenderer renderer(physics.model(), s);
  renderer.Render(0, physics.mutable_data(), 5, &again);
  renderer.Render(0, physics.mutable_data(), 6, &later);
  EXPECT_EQ(first, again);
  // The noise is drawn per state: another seq, other noise.
  EXPECT_NE(first, later);
}

// Two simulations rendering cameras in one process (Python, the studio):
// the one that goes first must not take the other's display with it.
TEST(CameraRenderer, AContextOutlivesAnotherOnTheSameDisplay) {
  const Scenario s = RedBallAhead(0.4);
  Physics physics(s);
  auto first = std::make_unique<GlContext>();
  GlContext second;
  first.reset();
  second.MakeCurrent();
  CameraImageRenderer renderer(physics.model(), s);
  std::vector<std::uint8_t> rgb;
  renderer.Render(0, physics.mutable_data(), 0, &rgb);
  EXPECT_GT(RedShare(rgb, 80, 60, 30, 50), 0.1);
}

// A pitch snake (orange modules) and, 1 m to its right, a static post
// `along` m ahead of the snake's middle carrying a fixed camera on its left
// face, looking at the snake across the ground, 20 degrees down.
Scenario PostWatchingASnake(double along) {
  ChainScenarioOptions options;
  options.chain.name = "crawler";
  options.chain.modules = 4;
  options.chain.pattern = ChainPattern::kPitch;
  Scenario s = MakeChainScenario(options);
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  int frames = 0;
  for (const Module& m : s.robots[0].modules) {
    for (const Frame& f : m.frames) {
      middle += f.position;
      ++frames;
    }
  }
  middle /= frames;
  SceneObject post;
  post.guid = "post";
  post.size = Eigen::Vector3d(0.04, 0.04, 0.04);
  post.position = Eigen::Vector3d(middle.x() + along, middle.y() - 1.0, 0.4);
  post.is_static = true;
  Camera camera;
  camera.sensor_position = 1;  // left (+y): toward the snake
  camera.tilt = 20;
  camera.width = 80;
  camera.height = 60;
  post.cameras.push_back(camera);
  s.scene_objects.push_back(post);
  return s;
}

// Fraction of pixels in columns [x0, x1) of the pitch modules' orange.
double OrangeShare(const std::vector<std::uint8_t>& rgb, int width, int height,
                   int x0, int x1) {
  int orange = 0, all = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
      orange += p[0] > 100 && p[0] > 1.2 * p[1] && p[1] > 2 * p[2];
      ++all;
    }
  }
  return static_cast<double>(orange) / all;
}

// A fixed camera on a static scene object (a user's CCTV view of the run):
// the snake it looks at is in the middle of its picture, and to the left
// once the post stands farther along the snake.
TEST(CameraRenderer, AFixedSceneObjectCameraSeesTheRobotWhereItStands) {
  GlContext gl;
  const Scenario s = PostWatchingASnake(0);
  Physics physics(s);
  CameraImageRenderer renderer(physics.model(), s);
  ASSERT_EQ(renderer.cameras().size(), 1u);
  const ScenarioCamera& c = renderer.cameras()[0];
  EXPECT_EQ(c.name, "scene/obj0/camera");
  EXPECT_EQ(c.owner, "scene");
  EXPECT_EQ(c.robot, -1);
  EXPECT_EQ(c.scene_object, 0);
  EXPECT_EQ(renderer.Find("scene", 0), 0);
  std::vector<std::uint8_t> rgb;
  renderer.Render(0, physics.mutable_data(), 0, &rgb);
  ASSERT_EQ(rgb.size(), 80u * 60 * 3);
  EXPECT_GT(OrangeShare(rgb, 80, 60, 30, 50), 0.02);
  EXPECT_LT(OrangeShare(rgb, 80, 60, 0, 12), 0.002);
  EXPECT_LT(OrangeShare(rgb, 80, 60, 68, 80), 0.002);

  // The post 0.6 m farther along +x: the picture's right is +x, so the
  // snake is now on its left.
  const Scenario moved = PostWatchingASnake(0.6);
  Physics moved_physics(moved);
  CameraImageRenderer moved_renderer(moved_physics.model(), moved);
  moved_renderer.Render(0, moved_physics.mutable_data(), 0, &rgb);
  EXPECT_GT(OrangeShare(rgb, 80, 60, 0, 30), 0.02);
  EXPECT_LT(OrangeShare(rgb, 80, 60, 50, 80), 0.002);
}

// A picture depends on the state and the camera alone, not on what was
// rendered before: MuJoCo lights the scene from the camera of the
// previous picture unless the renderer moves its camera first.
TEST(CameraRenderer, APictureIsTheSameWhicheverCameraWasRenderedBefore) {
  GlContext gl;
  Scenario s = PostWatchingASnake(0);
  s.scene_objects.push_back(s.scene_objects[0]);
  s.scene_objects[1].guid = "second post";
  s.scene_objects[1].position.y() += 2.0;  // the other side, looking back
  s.scene_objects[1].cameras[0].sensor_position = 3;
  Physics physics(s);
  CameraImageRenderer renderer(physics.model(), s);
  ASSERT_EQ(renderer.cameras().size(), 2u);
  std::vector<std::uint8_t> first, other, again;
  renderer.Render(0, physics.mutable_data(), 0, &first);
  renderer.Render(1, physics.mutable_data(), 0, &other);
  renderer.Render(0, physics.mutable_data(), 0, &again);
  EXPECT_EQ(first, again);
  CameraImageRenderer fresh(physics.model(), s);
  fresh.Render(0, physics.mutable_data(), 0, &again);
  EXPECT_EQ(first, again);
}

// A camera on a loose sensor module (no robot) renders as a robot's does.
TEST(CameraRenderer, ALooseSensorModulesCameraSeesTheBallAhead) {
  GlContext gl;
  Scenario s = RedBallAhead(0.4);
  // The robot's camera goes; a loose sensor module 1 m to the left looks
  // at a second red ball 0.4 m ahead of it.
  s.robots[0].sensor_modules[0].cameras.clear();
  SensorModule eye;
  eye.guid = "loose eye";
  eye.position =
      s.robots[0].sensor_modules[0].position + Eigen::Vector3d(0, 1.0, 0);
  Camera camera;
  camera.width = 80;
  camera.height = 60;
  eye.cameras.push_back(camera);
  s.loose_sensor_modules.push_back(eye);
  SceneObject ball = s.scene_objects[0];
  ball.guid = "second ball";
  ball.position.y() += 1.0;
  s.scene_objects.push_back(ball);
  Physics physics(s);
  CameraImageRenderer renderer(physics.model(), s);
  ASSERT_EQ(renderer.cameras().size(), 1u);
  EXPECT_EQ(renderer.cameras()[0].name, "loose/sm0/camera");
  EXPECT_EQ(renderer.cameras()[0].owner, "loose");
  EXPECT_EQ(renderer.cameras()[0].sensor_module, 0);
  std::vector<std::uint8_t> rgb;
  renderer.Render(0, physics.mutable_data(), 0, &rgb);
  EXPECT_GT(RedShare(rgb, 80, 60, 30, 50), 0.1);
  EXPECT_LT(RedShare(rgb, 80, 60, 0, 15), 0.01);
  EXPECT_LT(RedShare(rgb, 80, 60, 65, 80), 0.01);
}

// Every camera of a scenario, numbered per owner as camera_image_t
// numbers them: robots', then the loose sensor modules', then the scene
// objects'.
TEST(CameraRenderer, ScenarioCamerasListsEveryOwnersCamerasFromZero) {
  Scenario s = RedBallAhead(0.4);
  s.robots[0].sensor_modules[0].cameras.emplace_back().sensor_position = 2;
  SensorModule eye;
  eye.guid = "loose eye";
  eye.cameras.emplace_back();
  s.loose_sensor_modules.push_back(eye);
  s.scene_objects[0].cameras.emplace_back();
  s.scene_objects[0].cameras.emplace_back().sensor_position = 2;
  const std::vector<ScenarioCamera> cameras = ScenarioCameras(s);
  std::vector<std::string> seen;
  for (const ScenarioCamera& c : cameras) {
    seen.push_back(c.owner + " " + std::to_string(c.camera) + " " + c.name +
                   " " + c.part_guid);
  }
  EXPECT_EQ(seen,
            (std::vector<std::string>{
                "eye 0 eye/sm0/camera " + s.robots[0].sensor_modules[0].guid,
                "eye 1 eye/sm0/camera1 " + s.robots[0].sensor_modules[0].guid,
                "loose 0 loose/sm0/camera loose eye",
                "scene 0 scene/obj0/camera ball",
                "scene 1 scene/obj0/camera1 ball"}));
}

}  // namespace
}  // namespace mrsim
