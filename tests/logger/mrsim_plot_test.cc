// mrsim-plot as a real program: a PNG from a CSV, a clear error for a
// column that is not there.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

TEST(PlotProcess, MrsimPlotWritesThePngAndNamesABadColumn) {
  const std::string dir = testing::TempDir("plot_process");
  const std::string csv = dir + "/s.csv";
  {
    std::ofstream out(csv);
    out << "time,sensor_module0.distance0\n";
    for (int i = 0; i < 100; ++i)
      out << 0.01 * i << "," << 3 - 0.02 * i << "\n";
  }
  const std::string exe = testing::BinaryPath("logger/process/mrsim-plot");
  testing::ChildProcess ok(
      {exe, csv, "--x", "time", "--y", "sensor_module0.distance0", "--title",
       "closing on the ball", "-o", dir + "/d.png"},
      dir + "/ok.txt");
  ASSERT_EQ(ok.Wait(30), 0) << ok.Output();
  const cv::Mat img = cv::imread(dir + "/d.png");
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 960);
  EXPECT_EQ(img.rows, 600);

  testing::ChildProcess bad(
      {exe, csv, "--y", "sensor_module0.distance9", "-o", dir + "/e.png"},
      dir + "/bad.txt");
  EXPECT_EQ(bad.Wait(30), 2);
  EXPECT_NE(bad.Output().find("sensor_module0.distance9"), std::string::npos)
      << bad.Output();
}

}  // namespace
}  // namespace mrsim
