// The real mrsim-studio under its own Xvfb, driven by OS-level input
// (xdotool): a mesh picked for every pitch module, STL exported into a
// folder, and overlapping parts counted and drawn red.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/embed_assets.h"
#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/export/stl_export.h"
#include "sim_core/mesh/triangle_mesh.h"
#include "tests/common/child_process.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;

std::string Studio() { return BinaryPath("studio/mrsim-studio"); }

bool HaveX() {
  return fs::exists("/usr/bin/Xvfb") && fs::exists("/usr/bin/xdotool");
}

class StudioPrintTest : public ::testing::Test {
 protected:
  // The studio on a private display with a copy of the case study (and
  // whatever `prepare` adds to its folder).
  void Start(const std::string& name, const std::string& source = SourcePath(
                                          "scenarios/case_study.xml")) {
    dir_ = TempDir(name);
    file_ = dir_ + "/case_study.xml";
    fs::copy_file(source, file_);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    studio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{Studio(), "--layout-dump", layout_, file_},
        dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
  }

  // Clicks a recorded widget once the window has the pointer over it.
  void Click(const std::string& widget) {
    int x = 0, y = 0;
    ASSERT_TRUE(WidgetCentre(layout_, widget, &x, &y)) << widget;
    ASSERT_TRUE(ClickWhenThere(layout_, x, y)) << widget;
  }

  // Opens the file dialog with `button` and waits until it takes clicks
  // (its widgets are in the layout dump from then on).
  void OpenFileDialog(const std::string& button) {
    Click(button);
    ASSERT_TRUE(WaitForLayout(layout_, "file dialog", "ready"))
        << "after " << button << ": " << ReadLayout(layout_)["modal"];
  }

  std::string dir_, file_, layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

TEST_F(StudioPrintTest, PickAMeshForAllPitchModules) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  Start("studio_print_mesh");
  {
    std::ofstream out(dir_ + "/link.stl", std::ios::binary);
    out << BinaryStl(BoxMesh(Eigen::Vector3d(0.07, 0.05, 0.05)), 1.0, "link");
  }
  // Selected in the chain list, as a student picks a part to change.
  Click("row module 0 0");
  ASSERT_TRUE(WaitForLayout(layout_, "selected", "module 0 0"));
  OpenFileDialog("Mesh for all of kind...");
  ASSERT_EQ(ReadLayout(layout_)["file folder"], dir_);
  // One click at a time: two clicks in one frame would be one click at
  // the second place.
  Click("entry link.stl");
  ASSERT_TRUE(WaitForLayout(layout_, "file typed", "link.stl"));
  Click("file ok");
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "none"))
      << ReadLayout(layout_)["message"];
  ASSERT_TRUE(WaitForLayout(layout_, "revision", "1"))
      << ReadLayout(layout_)["message"];
  EXPECT_EQ(ReadLayout(layout_)["overlaps"], "0");
  Click("Save");
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0")) << studio_->Output();
  // A design is one file by default: the mesh travels inside it.
  EXPECT_EQ(ReadLayout(layout_)["embed"], "1");
  const Scenario saved = ReadScenarioFile(file_);
  int pitch = 0;
  for (const Module& m : saved.robots[0].modules) {
    for (const Frame& f : m.frames) {
      if (m.axis == Axis::kPitch) {
        EXPECT_TRUE(IsEmbeddedMesh(f.shape)) << f.shape.substr(0, 40);
      } else {
        EXPECT_EQ(f.shape, "Box");
      }
    }
    pitch += m.axis == Axis::kPitch;
  }
  EXPECT_GE(pitch, 2);
  studio_->Stop();
}

// A mesh drawn in millimetres makes its module 1000 times too big: the
// Design panel says so and its button scales the mesh by 0.001.
TEST_F(StudioPrintTest, AMeshInMillimetresIsOfferedScaleByOneThousandth) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string src = TempDir("studio_mesh_mm_src");
  {
    // 70 x 50 x 50 mm, as a CAD program exports it.
    std::ofstream out(src + "/link_mm.stl", std::ios::binary);
    out << BinaryStl(BoxMesh(Eigen::Vector3d(70, 50, 50)), 1.0, "link");
  }
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  for (Frame& f : s.robots[0].modules[0].frames) {
    f.shape = src + "/link_mm.stl";
    f.scale = Eigen::Vector3d::Ones();
  }
  WriteScenarioFile(s, src + "/mm.xml");
  Start("studio_mesh_mm", src + "/mm.xml");
  ASSERT_TRUE(WaitForLayout(layout_, "oversized meshes", "1"));
  // The panel shows the offer from the frame after the mesh is measured.
  ASSERT_TRUE(WaitUntil(
      [&] { return ReadLayout(layout_).count("widget scale by 0.001") > 0; },
      60));
  Click("scale by 0.001");
  ASSERT_TRUE(WaitForLayout(layout_, "oversized meshes", "0"))
      << ReadLayout(layout_)["message"];
  Click("Save");
  ASSERT_TRUE(WaitForLayout(layout_, "dirty", "0")) << studio_->Output();
  const Scenario saved = ReadScenarioFile(file_);
  for (const Frame& f : saved.robots[0].modules[0].frames) {
    EXPECT_NEAR(f.scale.x(), 0.001, 1e-12);
  }
  studio_->Stop();
}

// "Embed terrain and meshes" shows how the opened file was saved: ticked
// for a file that carries its meshes, unticked for one that names files.
TEST_F(StudioPrintTest, EmbeddingShowsHowTheFileWasSaved) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string src = TempDir("studio_embed_state_src");
  {
    std::ofstream out(src + "/link.stl", std::ios::binary);
    out << BinaryStl(BoxMesh(Eigen::Vector3d(0.07, 0.05, 0.05)), 1.0, "link");
  }
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  for (Frame& f : s.robots[0].modules[0].frames) f.shape = src + "/link.stl";
  WriteScenarioFile(s, src + "/named.xml");
  Start("studio_embed_state_named", src + "/named.xml");
  EXPECT_TRUE(WaitForLayout(layout_, "embed", "0"));
  studio_->Stop();
  s.base_dir = src;
  EmbedAssetFiles(s);
  WriteScenarioFile(s, src + "/embedded.xml");
  Start("studio_embed_state_embedded", src + "/embedded.xml");
  EXPECT_TRUE(WaitForLayout(layout_, "embed", "1"));
  studio_->Stop();
}

TEST_F(StudioPrintTest, ExportStlIntoAFolder) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  Start("studio_print_export");
  OpenFileDialog("Export STL...");
  // The folder name is filled in: beside the design, named after it.
  EXPECT_EQ(ReadLayout(layout_)["file folder"], dir_);
  EXPECT_EQ(ReadLayout(layout_)["file typed"], "case_study_stl");
  Click("file ok");
  ASSERT_TRUE(WaitForLayout(layout_, "modal", "none"))
      << ReadLayout(layout_)["message"];
  const std::string out = dir_ + "/case_study_stl";
  const StlExport expected = ExportStl(ReadScenarioFile(file_));
  int count = 0;
  for (const PrintedPart& p : expected.parts) count += p.count;
  ASSERT_TRUE(WaitForLayout(layout_, "message",
                            "exported " + std::to_string(count) + " parts (" +
                                std::to_string(expected.parts.size()) +
                                " distinct) to " + out))
      << ReadLayout(layout_)["message"];
  // The same bytes as the tested library writes (watertight, right size:
  // tests/scenario/stl_export_test.cc), parts.csv among them.
  ASSERT_TRUE(fs::exists(out + "/parts.csv"));
  int stls = 0;
  for (const auto& [name, bytes] : expected.files) {
    std::ifstream in(out + "/" + name, std::ios::binary);
    ASSERT_TRUE(in.good()) << name;
    std::stringstream read;
    read << in.rdbuf();
    EXPECT_TRUE(read.str() == bytes) << name;
    stls += fs::path(name).extension() == ".stl";
  }
  EXPECT_GE(stls, 2) << "parts and the assembled robot";
  studio_->Stop();
}

// The case study with a static crate `gap` m to the side of module 1
// (negative: into it), written to `dir`.
std::string CaseStudyWithCrate(const std::string& dir, double gap) {
  Scenario s = ReadScenarioFile(SourcePath("scenarios/case_study.xml"));
  SceneObject crate;
  crate.guid = "crate";
  crate.is_static = true;
  crate.size = Eigen::Vector3d(0.06, 0.06, 0.06);
  crate.position =
      s.robots[0].modules[1].position + Eigen::Vector3d(0, 0.055 + gap, 0.01);
  s.scene_objects.push_back(crate);
  const std::string file = dir + "/crate.xml";
  WriteScenarioFile(s, file);
  return file;
}

// REQ-1.2.8: Run refuses a design whose parts overlap at the start and
// says why beside the button, until the user ticks the box that allows it
// (the words of mrsim-sim's --allow-overlap).
TEST_F(StudioPrintTest, RunSaysWhyItRefusesOverlappingPartsUntilAllowed) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  const std::string source =
      CaseStudyWithCrate(TempDir("studio_run_overlap_src"), -0.01);
  Start("studio_run_overlap", source);
  ASSERT_TRUE(Xdotool({"mousemove", "640", "400"}));
  ASSERT_TRUE(Xdotool({"key", "F5"}));  // the Run panel
  ASSERT_TRUE(WaitUntil(
      [&] {
        return ReadLayout(layout_)["run refused"].find(
                   "scene object 'crate'") != std::string::npos;
      },
      60))
      << ReadLayout(layout_)["run refused"];
  EXPECT_NE(ReadLayout(layout_)["run refused"].find(" mm"), std::string::npos);
  // Every part by its name: the robot's, and its frame as the inspector
  // titles it, not by index.
  const std::string refused = ReadLayout(layout_)["run refused"];
  EXPECT_NE(refused.find("robot 'case_study' module 1 "), std::string::npos)
      << refused;
  EXPECT_TRUE(refused.find("front frame") != std::string::npos ||
              refused.find("back frame") != std::string::npos)
      << refused;
  Click("checkbox allow overlap");
  EXPECT_TRUE(WaitForLayout(layout_, "run refused", ""))
      << ReadLayout(layout_)["run refused"];
  studio_->Stop();
}

// Red pixels in the 3-D view of the case study with a crate beside
// module 1, `gap` m to its side (objects are red themselves; parts
// overlapping are drawn red on top).
int RedPixelsWithCrate(const std::string& name, double gap, bool* overlaps) {
  const std::string dir = TempDir(name);
  const std::string file = CaseStudyWithCrate(dir, gap);
  const Scenario s = ReadScenarioFile(file);
  *overlaps = !FindOverlaps(s).empty();
  const std::string png = dir + "/crate.png";
  unsetenv("DISPLAY");
  ChildProcess studio({Studio(), "--screenshot", png, file},
                      dir + "/studio.log");
  EXPECT_EQ(studio.Wait(180), 0) << studio.Output();
  const cv::Mat image = cv::imread(png);
  if (image.empty()) return -1;
  cv::Mat hsv, low, high;
  cv::cvtColor(image(cv::Rect(340, 40, 530, 700)), hsv, cv::COLOR_BGR2HSV);
  cv::inRange(hsv, cv::Scalar(0, 150, 100), cv::Scalar(6, 255, 255), low);
  cv::inRange(hsv, cv::Scalar(174, 150, 100), cv::Scalar(180, 255, 255), high);
  return cv::countNonZero(low) + cv::countNonZero(high);
}

TEST(StudioPrintScreenshot, OverlappingPartsAreDrawnRed) {
  bool overlapping = false, apart = true;
  const int touching =
      RedPixelsWithCrate("studio_print_overlap", -0.01, &overlapping);
  const int clear = RedPixelsWithCrate("studio_print_clear", 0.3, &apart);
  ASSERT_TRUE(overlapping);
  ASSERT_FALSE(apart);
  EXPECT_GT(touching, clear + 300) << "overlapping module not drawn red";
}

}  // namespace
}  // namespace mrsim::testing
