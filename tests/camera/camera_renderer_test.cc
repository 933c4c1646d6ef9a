// What a robot's camera sees, rendered for real (EGL, Mesa's llvmpipe, no
// display) from the physics' own poses: a red ball ahead is red in the
// middle of the picture, to the side once the robot has turned, and the
// same picture comes out bit for bit for the same state.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
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

}  // namespace
}  // namespace mrsim
