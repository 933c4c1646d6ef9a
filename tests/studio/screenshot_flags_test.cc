// mrsim-studio --screenshot with --select and --drag: pictures of what
// only a mouse shows (the handles of a selected object, a palette module
// on its way to the robot, an object being dragged), off-screen.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/common/child_process.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

std::string Studio() { return BinaryPath("studio/mrsim-studio"); }
std::string CaseStudy() { return SourcePath("scenarios/case_study.xml"); }

// Runs the studio off-screen with `flags`; the layout dump of its last
// frame.
std::map<std::string, std::string> Shot(const std::string& name,
                                        std::vector<std::string> flags,
                                        cv::Mat* image = nullptr) {
  const std::string dir = TempDir(name);
  const std::string png = dir + "/shot.png", layout = dir + "/layout.txt";
  unsetenv("DISPLAY");
  std::vector<std::string> argv = {Studio(), "--screenshot", png,
                                   "--layout-dump", layout};
  argv.insert(argv.end(), flags.begin(), flags.end());
  argv.push_back(CaseStudy());
  ChildProcess studio(argv, dir + "/studio.log");
  EXPECT_EQ(studio.Wait(180), 0) << studio.Output();
  if (image) *image = cv::imread(png);
  return ReadLayout(layout);
}

bool Point(const std::string& text, int* x, int* y) {
  std::istringstream in(text);
  return static_cast<bool>(in >> *x >> *y);
}

// Started with no file, as the desktop menu starts it: "New robot from
// template" is up, so a new user starts from a robot, not an empty world;
// with a file it is not.
TEST(StudioScreenshotFlags, WithoutAFileTheTemplateDialogIsUp) {
  const std::string dir = TempDir("studio_shot_no_file");
  const std::string png = dir + "/shot.png", layout = dir + "/layout.txt";
  unsetenv("DISPLAY");
  ChildProcess studio({Studio(), "--screenshot", png, "--layout-dump", layout},
                      dir + "/studio.log");
  ASSERT_EQ(studio.Wait(180), 0) << studio.Output();
  auto state = ReadLayout(layout);
  EXPECT_EQ(state["modal"], "template");
  EXPECT_FALSE(state["widget Create"].empty()) << "no Create button";
  EXPECT_EQ(Shot("studio_shot_file", {})["modal"], "none");
}

TEST(StudioScreenshotFlags, SelectShowsTheMoveHandleOfTheObject) {
  cv::Mat image;
  auto layout = Shot("studio_shot_select", {"--select", "ball"}, &image);
  EXPECT_EQ(layout["selected"], "object 0 0");
  int x = 0, y = 0;
  ASSERT_TRUE(Point(layout["handle move"], &x, &y)) << "no move handle";
  ASSERT_FALSE(image.empty());
  // The handle is a white disc.
  const cv::Vec3b centre = image.at<cv::Vec3b>(y, x);
  EXPECT_GT(centre[0] + centre[1] + centre[2], 3 * 200)
      << "no white disc at " << x << " " << y;
}

TEST(StudioScreenshotFlags, DragShowsAPaletteModuleOnItsWayAndKeepsTheDesign) {
  auto still = Shot("studio_shot_still", {});
  int x = 0, y = 0;
  std::istringstream palette(still["widget pitch module"]);
  int left = 0, top = 0, w = 0, h = 0;
  ASSERT_TRUE(palette >> left >> top >> w >> h) << "no palette button";
  std::istringstream view(still["panel view"]);
  int vx = 0, vy = 0, vw = 0, vh = 0;
  ASSERT_TRUE(view >> vx >> vy >> vw >> vh);
  x = vx + vw / 2;
  y = vy + vh / 2;
  auto dragging =
      Shot("studio_shot_drag",
           {"--drag", std::to_string(left + w / 2), std::to_string(top + h / 2),
            std::to_string(x), std::to_string(y)});
  EXPECT_EQ(dragging["drag"], "new");
  EXPECT_EQ(dragging["mouse"],
            std::to_string(x) + " " + std::to_string(y) + " down");
  // Still held: nothing dropped, nothing changed.
  EXPECT_EQ(dragging["dirty"], "0");
  EXPECT_EQ(dragging["revision"], "0");
}

TEST(StudioScreenshotFlags, DragOnTheMoveHandleMovesTheObjectInThePicture) {
  auto selected = Shot("studio_shot_handle", {"--select", "ball"});
  int x = 0, y = 0;
  ASSERT_TRUE(Point(selected["handle move"], &x, &y));
  auto moving =
      Shot("studio_shot_move",
           {"--select", "ball", "--drag", std::to_string(x), std::to_string(y),
            std::to_string(x + 80), std::to_string(y + 30)});
  EXPECT_EQ(moving["handle drag"], "move");
  EXPECT_NE(moving["handle move"], selected["handle move"]);
  EXPECT_EQ(moving["dirty"], "0") << "a drag is one edit, on release";
}

TEST(StudioScreenshotFlags, FullViewHidesBothPanels) {
  auto layout = Shot("studio_shot_full", {"--full-view"});
  EXPECT_EQ(layout["panel left"], "hidden");
  EXPECT_EQ(layout["panel right"], "hidden");
  EXPECT_EQ(layout["panel view"].substr(0, 2), "0 ") << layout["panel view"];
}

TEST(StudioScreenshotFlags, BadSelectExits2AndDragNeedsAScreenshot) {
  const std::string dir = TempDir("studio_shot_bad");
  unsetenv("DISPLAY");
  ChildProcess bad({Studio(), "--screenshot", dir + "/a.png", "--select",
                    "crate", CaseStudy()},
                   dir + "/select.log");
  EXPECT_EQ(bad.Wait(120), 2);
  EXPECT_NE(bad.Output().find("--select: nothing named 'crate'"),
            std::string::npos)
      << bad.Output();
  ChildProcess no_shot({Studio(), "--drag", "1", "2", "3", "4", CaseStudy()},
                       dir + "/drag.log");
  // A command-line error: 2, as every mrsim tool says bad usage.
  EXPECT_EQ(no_shot.Wait(60), 2);
  EXPECT_NE(no_shot.Output().find("--drag requires --screenshot"),
            std::string::npos)
      << no_shot.Output();
}

}  // namespace
}  // namespace mrsim::testing
