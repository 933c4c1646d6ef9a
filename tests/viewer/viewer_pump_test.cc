// The frame pump and the video writer in process.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/viewer/viewer_test_util.h"
#include "viewer/frame_pump.h"
#include "viewer/frame_writer.h"
#include "viewer/gl_context.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

ViewerOptions SmallView() {
  ViewerOptions options;
  options.width = 160;
  options.height = 120;
  options.gait = "test";
  return options;
}

TEST(ViewerFrameWriter, DefaultMp4IsH264ThatBrowsersPlay) {
  const std::string path = TempDir("viewer_h264") + "/video.mp4";
  {
    auto writer = FrameWriter::Video(path, 10, 160, 120);
    EXPECT_EQ(writer->codec(), "avc1");
    cv::Mat frame(120, 160, CV_8UC3);
    for (int k = 0; k < 5; ++k) {
      frame.setTo(cv::Scalar(40 * k, 80, 200 - 30 * k));
      writer->Write(frame, k);
    }
  }
  // The sample description box of an H.264 track is an 'avc1' entry with
  // its 'avcC' configuration; MPEG-4 Part 2 would be 'mp4v'.
  const std::string bytes = ReadBytes(path);
  EXPECT_NE(bytes.find("avc1"), std::string::npos);
  EXPECT_NE(bytes.find("avcC"), std::string::npos);
  EXPECT_EQ(bytes.find("mp4v"), std::string::npos);
}

TEST(ViewerFramePump, RendersDueFramesOnceAndOpensTheOutputOnTheFirst) {
  GlContext gl;
  const Scenario scenario = testing::ViewerTestScenario();
  StateViewer viewer(scenario, SmallView());
  FrameScheduler scheduler(10.0, viewer.robot_count(), 8);
  std::mutex mutex;
  const std::string dir = TempDir("viewer_pump") + "/frames";
  int opened = 0;
  FramePump pump(
      &viewer, &scheduler,
      [&] {
        ++opened;
        return FrameWriter::Pngs(dir);
      },
      nullptr, 0, nullptr, &mutex);
  EXPECT_TRUE(pump.Drain());  // nothing due
  EXPECT_EQ(opened, 0);
  EXPECT_FALSE(fs::exists(dir));

  Physics physics(scenario);
  testing::DriveTo(&physics, 0.05);
  RobotState early = physics.ReadRobotState(0);
  scheduler.Push(0, 50000, early);
  testing::DriveTo(&physics, 0.35);
  scheduler.Push(0, 350000, physics.ReadRobotState(0));
  EXPECT_TRUE(pump.Drain());
  // Frames at 0.1, 0.2 and 0.3 s all show the state of 0.05 s: one render.
  EXPECT_EQ(opened, 1);
  EXPECT_EQ(pump.first_index(), 1);
  EXPECT_EQ(pump.frames(), 3);
  EXPECT_EQ(pump.rendered(), 1);
  const cv::Mat a = cv::imread(FrameWriter::PngName(dir, 1));
  const cv::Mat b = cv::imread(FrameWriter::PngName(dir, 3));
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(testing::MeanAbsDiff(a, b), 0.0);
  EXPECT_GT(testing::GreyStdDev(a), 5.0);
}

TEST(ViewerFramePump, StopsAtMaxFrames) {
  GlContext gl;
  const Scenario scenario = testing::ViewerTestScenario();
  StateViewer viewer(scenario, SmallView());
  FrameScheduler scheduler(10.0, viewer.robot_count(), 8);
  std::mutex mutex;
  FramePump pump(&viewer, &scheduler, nullptr, nullptr, 2, nullptr, &mutex);
  Physics physics(scenario);
  testing::DriveTo(&physics, 0.6);
  scheduler.Push(0, 600000, physics.ReadRobotState(0));
  scheduler.Push(0, 900000, physics.ReadRobotState(0));
  EXPECT_FALSE(pump.Drain());
  EXPECT_TRUE(pump.Done());
  EXPECT_EQ(pump.frames(), 2);
  EXPECT_EQ(pump.writer(), nullptr);
}

}  // namespace
}  // namespace mrsim
