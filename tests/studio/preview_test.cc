// The preview in-process, off-screen (EGL, software GL): after edits it
// shows exactly the model the physics builds from the saved file, and what
// it draws after rebuilding in place (context kept) equals a fresh window
// on that file.
#include "studio/ui/view/preview.h"

#include <GL/gl.h>
#include <gtest/gtest.h>

#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "studio/app/headless_studio.h"
#include "studio/design/design.h"
#include "studio/ui/studio_app.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 400;

std::vector<unsigned char> ModelBytes(const mjModel* m) {
  std::vector<unsigned char> bytes(mj_sizeModel(m));
  mj_saveModel(m, nullptr, bytes.data(), static_cast<int>(bytes.size()));
  return bytes;
}

AppOptions Options() {
  AppOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.recent_store = "-";
  return options;
}

// The 3-D view alone over the whole buffer, framed on the current model.
std::vector<unsigned char> Pixels(StudioApp* app, HeadlessStudio* studio) {
  studio->Frame();  // builds what changed
  app->preview().Reframe();
  app->preview().Render({0, 0, kWidth, kHeight}, true, {});
  glFinish();
  std::vector<unsigned char> rgb;
  app->preview().ReadPixels(kWidth, kHeight, &rgb);
  return rgb;
}

TEST(StudioPreview, AfterEditsShowsThePhysicsModelOfTheSavedFile) {
  const std::string path =
      mrsim::testing::TempDir("studio_preview_physics") + "/preview.xml";
  TemplateOptions options;
  options.chain.modules = 6;
  options.chain.pattern = ChainPattern::kPitchYaw;
  Design design;
  design.ApplyTemplate(options);
  StudioApp app(std::move(design), Options());
  HeadlessStudio studio(&app, kWidth, kHeight);
  studio.Frame();
  // Structural edits, field edits and an object: each rebuilds in place.
  Design& d = app.design();
  d.Select({SelectionKind::kModule, 0, 2});
  d.AddPart(NextPart::kSensorModule);
  studio.Frame();
  d.AddPart(NextPart::kYawModule, Where::kTail);
  studio.Frame();
  d.SetField({{SelectionKind::kModule, 0, 1}, "frames[0]", "mass"}, "0.07");
  studio.Frame();
  d.AddObject(ObjectKind::kBall);
  studio.Frame();
  d.SetField({{SelectionKind::kSceneObject, 0, 0}, "", "position"},
             "0.9 0.1 0.05");
  studio.Frame();
  ASSERT_EQ(app.build_error(), "");
  d.SaveAs(path);

  const Physics physics(ReadScenarioFile(path));
  ASSERT_NE(app.preview().model(), nullptr);
  EXPECT_EQ(ModelBytes(app.preview().model()), ModelBytes(physics.model()));
}

TEST(StudioPreview, RebuiltInPlaceDrawsLikeAFreshWindow) {
  const std::string path =
      mrsim::testing::TempDir("studio_preview_fresh") + "/fresh.xml";
  std::vector<unsigned char> after_edits, opened;
  {
    StudioApp edited(Design(), Options());
    HeadlessStudio studio(&edited, kWidth, kHeight);
    Design& d = edited.design();
    for (NextPart p : {NextPart::kPitchModule, NextPart::kSensorModule,
                       NextPart::kYawModule, NextPart::kPitchModule}) {
      d.AddPart(p);
      studio.Frame();
    }
    d.AddObject(ObjectKind::kBox);
    studio.Frame();
    d.SaveAs(path);
    d.Select({});
    after_edits = Pixels(&edited, &studio);
  }
  {
    StudioApp fresh(Design::Open(path), Options());
    HeadlessStudio studio(&fresh, kWidth, kHeight);
    fresh.design().Select({});
    opened = Pixels(&fresh, &studio);
  }
  ASSERT_EQ(after_edits.size(), opened.size());
  size_t differ = 0;
  for (size_t i = 0; i < opened.size(); ++i) {
    if (after_edits[i] != opened[i]) ++differ;
  }
  // llvmpipe filters the floor texture's grid lines a few pixels apart
  // after other frames were drawn (so even with the context made again);
  // a stale context (wrong texture, plane or buffer) differs everywhere.
  EXPECT_LT(differ, opened.size() / 200) << "of " << opened.size() << " bytes";
}

TEST(StudioPreview, CameraFramesTheGrowingRobotUntilTheUserMovesIt) {
  Design design;
  design.AddPart(NextPart::kPitchModule, Where::kTail);
  StudioApp app(std::move(design), Options());
  HeadlessStudio studio(&app, kWidth, kHeight);
  studio.Frame();
  Preview& preview = app.preview();
  const double one_module = preview.camera().distance;
  for (int k = 0; k < 8; ++k) {
    app.design().AddPart(NextPart::kPitchModule, Where::kTail);
  }
  studio.Frame();
  const double nine_modules = preview.camera().distance;
  EXPECT_GT(nine_modules, one_module * 1.5);
  // Once the user zooms, the camera is theirs: a new part leaves it alone.
  preview.Zoom(0.1);
  const mjvCamera held = preview.camera();
  app.design().AddPart(NextPart::kPitchModule, Where::kTail);
  studio.Frame();
  EXPECT_EQ(preview.camera().distance, held.distance);
  EXPECT_EQ(preview.camera().lookat[0], held.lookat[0]);
}

TEST(StudioPreview, LiveCameraMovesWithTheRobotUnlessTurnedOff) {
  TemplateOptions options;
  options.chain.modules = 5;
  Design design;
  design.ApplyTemplate(options);
  StudioApp app(std::move(design), Options());
  HeadlessStudio studio(&app, kWidth, kHeight);
  studio.Frame();
  Preview& preview = app.preview();
  const Scenario& scenario = app.design().scenario();
  const std::string name = scenario.robots[0].name;
  // A state of the design as the simulator reports it, then the same robot
  // carried 0.7 m along x and 0.2 m along y.
  const Physics physics(scenario);
  RobotState at_start = physics.ReadRobotState(0);
  RobotState moved = at_start;
  const Eigen::Vector3d shift(0.7, 0.2, 0.0);
  moved.com += shift;
  for (auto& pose : moved.modules) pose.position += shift;
  for (auto& pose : moved.frames) pose.position += shift;

  preview.ShowStates(scenario, {{name, at_start}}, nullptr);
  const mjvCamera before = preview.camera();
  preview.ShowStates(scenario, {{name, moved}}, nullptr);
  EXPECT_NEAR(preview.camera().lookat[0] - before.lookat[0], 0.7, 1e-9);
  EXPECT_NEAR(preview.camera().lookat[1] - before.lookat[1], 0.2, 1e-9);
  EXPECT_EQ(preview.camera().lookat[2], before.lookat[2]);
  EXPECT_EQ(preview.camera().distance, before.distance);

  // Turned off, the camera stays where the user left it.
  preview.SetTracking(false);
  const mjvCamera held = preview.camera();
  preview.ShowStates(scenario, {{name, at_start}}, nullptr);
  EXPECT_EQ(preview.camera().lookat[0], held.lookat[0]);
  EXPECT_EQ(preview.camera().lookat[1], held.lookat[1]);
}

}  // namespace
}  // namespace mrsim::studio
