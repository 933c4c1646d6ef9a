// What the studio changes in MuJoCo's drawing on software GL (llvmpipe)
// keeps the picture: the infinite floor drawn as one plane looks like
// MuJoCo's grid, and a released drag draws the design as before it.
#include "studio/ui/view/software_gl.h"

#include <GL/gl.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdlib>
#include <vector>

#include "studio/app/headless_studio.h"
#include "studio/design/design.h"
#include "studio/ui/view/preview.h"
#include "studio/ui/studio_app.h"
#include "tests/common/child_process.h"

namespace mrsim::studio {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 400;

AppOptions Options() {
  AppOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.recent_store = "-";
  return options;
}

// Bytes further apart than one step of rounding.
size_t Differ(const std::vector<unsigned char>& a,
              const std::vector<unsigned char>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (std::abs(a[i] - b[i]) > 1) ++n;
  }
  return n;
}

TEST(StudioSoftwareGl, FloorAsOnePlaneLooksLikeMujocosGrid) {
  StudioApp app(Design::Open(testing::SourcePath("scenarios/case_study.xml")),
                Options());
  HeadlessStudio studio(&app, kWidth, kHeight);
  studio.Frame();
  ASSERT_NE(app.preview().model(), nullptr);
  // A context, scene and data of our own on the preview's model, looking
  // down at the floor so it fills the view.
  mjModel* m = mj_copyModel(nullptr, app.preview().model());
  m->vis.global.offwidth = kWidth;
  m->vis.global.offheight = kHeight;
  mjData* d = mj_makeData(m);
  mj_kinematics(m, d);
  mj_camlight(m, d);
  mjvScene scene;
  mjv_defaultScene(&scene);
  mjv_makeScene(m, &scene, m->ngeom + 10);
  mjvOption option;
  mjv_defaultOption(&option);
  mjvCamera camera;
  mjv_defaultFreeCamera(m, &camera);
  camera.elevation = -25;
  camera.distance = 1.5;
  mjrContext context;
  mjr_defaultContext(&context);
  mjr_makeContext(m, &context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &context);
  const mjrRect view = {0, 0, kWidth, kHeight};
  auto draw = [&](bool coarse) {
    mjv_updateScene(m, d, &option, nullptr, &camera, mjCAT_ALL, &scene);
    scene.flags[mjRND_SHADOW] = 0;
    bool changed = false;
    if (coarse) {
      CoarsenInfinitePlanes(m, context, &scene);
      for (int i = 0; i < scene.ngeom; ++i) {
        changed |=
            scene.geoms[i].type == mjGEOM_PLANE && scene.geoms[i].dataid == -1;
      }
      EXPECT_TRUE(changed) << "the case study's floor is an infinite plane";
    }
    mjr_render(view, &scene, &context);
    glFinish();
    std::vector<unsigned char> rgb(3 * kWidth * kHeight);
    mjr_readPixels(rgb.data(), nullptr, view, &context);
    return rgb;
  };
  const std::vector<unsigned char> grid = draw(false);
  const std::vector<unsigned char> plane = draw(true);
  mjr_freeContext(&context);
  mjv_freeScene(&scene);
  mj_deleteData(d);
  mj_deleteModel(m);
  // The lights are directional and the texture repeats per metre either
  // way: at most a few bytes round differently.
  EXPECT_LT(Differ(grid, plane), grid.size() / 1000)
      << "of " << grid.size() << " bytes";
}

TEST(StudioSoftwareGl, ReleasedDragDrawsTheDesignAsBefore) {
  StudioApp app(Design::Open(testing::SourcePath("scenarios/case_study.xml")),
                Options());
  HeadlessStudio studio(&app, kWidth, kHeight);
  studio.Frame();
  ASSERT_FALSE(app.design().scenario().scene_objects.empty());
  Preview& preview = app.preview();
  auto draw = [&] {
    preview.Render({0, 0, kWidth, kHeight}, true, {});
    glFinish();
    std::vector<unsigned char> rgb;
    preview.ReadPixels(kWidth, kHeight, &rgb);
    return rgb;
  };
  const std::vector<unsigned char> before = draw();

  Eigen::Isometry3d move = Eigen::Isometry3d::Identity();
  move.translation() = Eigen::Vector3d(0.3, 0, 0);
  preview.ShowDrag({SelectionKind::kSceneObject, 0, 0}, move);
  const std::vector<unsigned char> dragging = draw();
  preview.EndDrag();
  const std::vector<unsigned char> after = draw();
  EXPECT_GT(Differ(before, dragging), 0u) << "the ball moved";
  // The ball back in place, and the floor's reflection (left out while
  // dragging on software GL) back too.
  EXPECT_EQ(Differ(before, after), 0u);
}

}  // namespace
}  // namespace mrsim::studio
