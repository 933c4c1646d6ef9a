// The Run panel's camera picture in process, off-screen (EGL, software GL,
// no display): CameraFeed shows what the chosen camera sees (the renderer
// mrsim-camera uses, from the poses the 3-D view draws), renders at the
// camera's rate in simulated time, keeps the chosen camera across rebuilds,
// and the studio fills it from its own preview when the Run panel shows.
#include "studio/ui/view/camera_feed.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/physics.h"
#include "studio/app/headless_studio.h"
#include "studio/design/design.h"
#include "studio/ui/studio_app.h"
#include "viewer/camera_image_renderer.h"
#include "viewer/gl_context.h"

namespace mrsim::studio {
namespace {

// A yaw snake with a sensor module in front of module 0 carrying a camera
// looking ahead (front face) and one looking left, and a red ball ahead.
Scenario RedBallAhead() {
  ChainScenarioOptions options;
  options.chain.name = "eye";
  options.chain.modules = 3;
  options.chain.pattern = ChainPattern::kYaw;
  options.chain.sensor_after = {-1};
  Scenario s = MakeChainScenario(options);
  SensorModule& head = s.robots[0].sensor_modules[0];
  Camera ahead;
  ahead.sensor_position = 4;
  ahead.width = 80;
  ahead.height = 60;
  ahead.rate = 10;
  head.cameras.push_back(ahead);
  Camera left = ahead;
  left.sensor_position = 1;
  head.cameras.push_back(left);
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d::Constant(0.1);
  ball.position =
      head.position + Eigen::Vector3d(0.4, 0, 0.05 - head.position.z());
  ball.is_static = true;
  ball.material_name = "red";
  s.scene_objects.push_back(ball);
  return s;
}

// Fraction of clearly red pixels in the middle third of the picture.
double RedInTheMiddle(const FeedPicture& p) {
  int red = 0, all = 0;
  for (int y = 0; y < p.height; ++y) {
    for (int x = p.width / 3; x < 2 * p.width / 3; ++x) {
      const std::uint8_t* c =
          &p.rgb[(static_cast<size_t>(y) * p.width + x) * 3];
      red += c[0] > 120 && c[0] > 2 * c[1] && c[0] > 2 * c[2];
      ++all;
    }
  }
  return static_cast<double>(red) / all;
}

TEST(StudioCameraFeed, ShowsWhatTheChosenCameraSeesAtItsRate) {
  GlContext gl;
  const Scenario s = RedBallAhead();
  Physics physics(s);
  CameraFeed feed;
  feed.SetModel(physics.model(), s, 1);
  ASSERT_EQ(feed.cameras().size(), 2u);
  EXPECT_EQ(feed.Labels(),
            (std::vector<std::string>{"eye camera 0: S0 front, 80x60",
                                      "eye camera 1: S0 left, 80x60"}));
  EXPECT_EQ(feed.texture(), 0u);

  ASSERT_TRUE(feed.Update(physics.mutable_data(), 0, 0));
  const FeedPicture& p = feed.picture();
  EXPECT_EQ(p.width, 80);
  EXPECT_EQ(p.height, 60);
  ASSERT_EQ(p.rgb.size(), 80u * 60 * 3);
  EXPECT_GT(RedInTheMiddle(p), 0.05);
  EXPECT_NE(feed.texture(), 0u);
  // The very picture mrsim-camera's renderer makes for that state.
  {
    CameraImageRenderer renderer(physics.model(), s);
    std::vector<std::uint8_t> rgb;
    renderer.Render(0, physics.mutable_data(), 0, &rgb);
    EXPECT_EQ(rgb, p.rgb);
  }

  // 10 pictures per simulated second: none before 0.1 s, one at it.
  EXPECT_FALSE(feed.Update(physics.mutable_data(), 0.05, 5));
  EXPECT_TRUE(feed.Update(physics.mutable_data(), 0.1, 10));
  EXPECT_FALSE(feed.Update(physics.mutable_data(), 0.15, 15));
  EXPECT_EQ(feed.picture().seq, 10);
  EXPECT_EQ(feed.rendered(), 2);
  // Another camera is due at once: the left one does not see the ball.
  feed.Select(1);
  EXPECT_TRUE(feed.Update(physics.mutable_data(), 0.15, 15));
  EXPECT_EQ(feed.picture().camera, 1);
  EXPECT_LT(RedInTheMiddle(feed.picture()), 0.01);
  // Time going back is a new run: its first picture comes at once.
  EXPECT_TRUE(feed.Update(physics.mutable_data(), 0.01, 1));
  feed.Select(7);  // clamped
  EXPECT_EQ(feed.selected(), 1);
}

TEST(StudioCameraFeed, KeepsTheChosenCameraWhenTheModelIsRebuilt) {
  GlContext gl;
  Scenario s = RedBallAhead();
  Physics physics(s);
  CameraFeed feed;
  feed.SetModel(physics.model(), s, 1);
  feed.Select(1);
  // The front camera goes: the left one is now the first, still chosen.
  s.robots[0].sensor_modules[0].cameras.erase(
      s.robots[0].sensor_modules[0].cameras.begin());
  Physics rebuilt(s);
  feed.SetModel(rebuilt.model(), s, 2);
  ASSERT_EQ(feed.cameras().size(), 1u);
  EXPECT_EQ(feed.selected(), 0);
  EXPECT_EQ(feed.picture().seq, -1);  // the old picture is gone
  EXPECT_TRUE(feed.Update(rebuilt.mutable_data(), 0, -1));
  // No cameras: nothing to show, nothing rendered.
  s.robots[0].sensor_modules[0].cameras.clear();
  Physics plain(s);
  feed.SetModel(plain.model(), s, 3);
  EXPECT_TRUE(feed.cameras().empty());
  EXPECT_FALSE(feed.Update(plain.mutable_data(), 1, 100));
  EXPECT_EQ(feed.error(), "");
}

// The studio fills the feed from its own 3-D view's model and poses when
// the Run panel shows: the design's pose before a run.
TEST(StudioCameraFeed, TheRunPanelShowsTheDesignsCameraPicture) {
  Design design;
  design.ApplyTemplate([] {
    TemplateOptions o;
    o.chain.modules = 3;
    o.chain.pattern = ChainPattern::kYaw;
    o.chain.sensor_after = {-1};
    return o;
  }());
  design.Select({SelectionKind::kSensorModule, 0, 0});
  design.AddCamera(4);
  design.AddObject(ObjectKind::kBall);
  AppOptions options;
  options.width = 960;
  options.height = 640;
  options.recent_store = "-";
  StudioApp app(std::move(design), options);
  HeadlessStudio studio(&app, 960, 640);
  studio.Frame();
  EXPECT_EQ(app.camera_feed().rendered(), 0);  // the inspector shows
  app.ShowRunPanel(true);
  for (int i = 0; i < 3; ++i) studio.Frame();
  ASSERT_EQ(app.camera_feed().cameras().size(), 1u);
  EXPECT_EQ(app.camera_feed().error(), "");
  EXPECT_GE(app.camera_feed().rendered(), 1);
  // One picture for the design's pose, not one per frame.
  const std::int64_t once = app.camera_feed().rendered();
  studio.Frame();
  EXPECT_EQ(app.camera_feed().rendered(), once);
  EXPECT_EQ(app.camera_feed().picture().width, Camera().width);
  EXPECT_NE(app.camera_feed().texture(), 0u);
}

}  // namespace
}  // namespace mrsim::studio
