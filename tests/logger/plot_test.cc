#include "logger/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "logger/log_plot_spec.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

bool IsColor(const cv::Vec3b& p, const cv::Scalar& c, int tol = 40) {
  return std::abs(p[0] - c[0]) < tol && std::abs(p[1] - c[1]) < tol &&
         std::abs(p[2] - c[2]) < tol;
}

bool IsDark(const cv::Vec3b& p) { return p[0] + p[1] + p[2] < 200; }

// Bounding box of the pixels of colour `c` inside `area`.
cv::Rect ColorExtent(const cv::Mat& img, const cv::Rect& area,
                     const cv::Scalar& c) {
  int x0 = INT32_MAX, y0 = INT32_MAX, x1 = -1, y1 = -1;
  for (int y = area.y; y <= area.y + area.height && y < img.rows; ++y) {
    for (int x = area.x; x <= area.x + area.width && x < img.cols; ++x) {
      if (IsColor(img.at<cv::Vec3b>(y, x), c, 20)) {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
    }
  }
  return x1 < 0 ? cv::Rect() : cv::Rect(x0, y0, x1 - x0, y1 - y0);
}

CsvColumns Sine() {
  CsvColumns d;
  d.names = {"time", "sensor_module0.distance0", "module0.z"};
  d.values.resize(3);
  for (int i = 0; i <= 1000; ++i) {
    const double t = 0.01 * i;  // 0..10 s
    d.values[0].push_back(t);
    d.values[1].push_back(2.0 + 1.5 * std::sin(t));  // 0.5 .. 3.5 m
    d.values[2].push_back(0.1 * t);
  }
  d.rows = 1001;
  return d;
}

TEST(Plot, NiceAxisCoversTheDataWithEvenRoundTicks) {
  for (auto [lo, hi] : std::vector<std::pair<double, double>>{
           {0.13, 9.7}, {-0.004, 0.0031}, {1e6, 1e6 + 3}, {5, 5}, {-7, -2}}) {
    const PlotAxis a = NiceAxis(lo, hi, 8);
    EXPECT_LE(a.min, lo);
    EXPECT_GE(a.max, hi);
    EXPECT_LT(a.min, a.max);
    ASSERT_GE(a.ticks.size(), 2u);
    ASSERT_EQ(a.ticks.size(), a.tick_labels.size());
    const double step = a.ticks[1] - a.ticks[0];
    for (size_t i = 1; i < a.ticks.size(); ++i) {
      EXPECT_NEAR(a.ticks[i] - a.ticks[i - 1], step, step * 1e-9);
      // The label says the tick's value.
      EXPECT_NEAR(std::stod(a.tick_labels[i]), a.ticks[i], step * 1e-3)
          << a.tick_labels[i];
    }
    EXPECT_LE(a.ticks.size(), 9u);
  }
  const PlotAxis a = NiceAxis(0.13, 9.7, 8);
  EXPECT_EQ(a.min, 0);
  EXPECT_EQ(a.max, 10);
  EXPECT_EQ(a.tick_labels.front(), "0");
  EXPECT_EQ(a.tick_labels.back(), "10");
}

TEST(Plot, ChartHasAxesLabelsAndTheCurveSpansTheDataRange) {
  PlotOptions opt;
  opt.x = "time";
  opt.y = {"sensor_module0.distance0"};
  opt.width = 800;
  opt.height = 500;
  cv::Mat img;
  const PlotResult r = RenderPlot(Sine(), opt, &img);
  ASSERT_EQ(img.cols, 800);
  ASSERT_EQ(img.rows, 500);
  EXPECT_EQ(r.x.min, 0);
  EXPECT_EQ(r.x.max, 10);
  EXPECT_LE(r.y.min, 0.5);
  EXPECT_GE(r.y.max, 3.5);
  EXPECT_GT(r.y.min, -0.1);
  EXPECT_LT(r.y.max, 4.1);
  EXPECT_EQ(r.x.label, "time [s]");
  EXPECT_EQ(r.y.label, "sensor_module0.distance0 [m]");
  EXPECT_TRUE(r.lines);
  EXPECT_EQ(r.points, 1001u);

  // Both axes are drawn: dark pixels along the bottom and left edges.
  const cv::Rect& a = r.area;
  int bottom = 0, left = 0;
  for (int x = a.x; x < a.x + a.width; ++x) {
    bottom += IsDark(img.at<cv::Vec3b>(a.y + a.height, x));
  }
  for (int y = a.y; y < a.y + a.height; ++y)
    left += IsDark(img.at<cv::Vec3b>(y, a.x));
  EXPECT_GT(bottom, a.width * 9 / 10);
  EXPECT_GT(left, a.height * 9 / 10);

  // The curve spans the whole time axis and the data's height.
  const cv::Rect ext = ColorExtent(img, a, r.colors[0]);
  auto px = [&](double v) {
    return a.x + (v - r.x.min) / (r.x.max - r.x.min) * a.width;
  };
  auto py = [&](double v) {
    return a.y + a.height - (v - r.y.min) / (r.y.max - r.y.min) * a.height;
  };
  EXPECT_NEAR(ext.x, px(0), 3);
  EXPECT_NEAR(ext.x + ext.width, px(10), 3);
  EXPECT_NEAR(ext.y, py(3.5), 3);
  // The legend sample has the curve's colour too, so the bottom is checked
  // on the curve only: its lowest point is at sin = -1.
  EXPECT_GE(ext.y + ext.height, py(0.5) - 3);

  // Text: title above the area, tick labels below it.
  int title_ink = 0, tick_ink = 0;
  for (int y = 0; y < a.y - 4; ++y) {
    for (int x = 0; x < img.cols; ++x)
      title_ink += IsDark(img.at<cv::Vec3b>(y, x));
  }
  for (int y = a.y + a.height + 8; y < a.y + a.height + 28; ++y) {
    for (int x = a.x; x < a.x + a.width; ++x) {
      tick_ink += IsDark(img.at<cv::Vec3b>(y, x));
    }
  }
  EXPECT_GT(title_ink, 100);
  EXPECT_GT(tick_ink, 100);
}

TEST(Plot, ColumnAgainstColumnUsesPointsAndItsOwnRange) {
  CsvColumns d = Sine();
  PlotOptions opt;
  opt.x = "sensor_module0.distance0";
  opt.y = {"module0.z"};
  cv::Mat img;
  const PlotResult r = RenderPlot(d, opt, &img);
  EXPECT_FALSE(r.lines);
  EXPECT_LE(r.x.min, 0.5);
  EXPECT_GE(r.x.max, 3.5);
  EXPECT_LE(r.y.min, 0.0);
  EXPECT_GE(r.y.max, 1.0);
  EXPECT_EQ(r.x.label, "sensor_module0.distance0 [m]");
}

TEST(Plot, XTickLabelsOfATinyRangeStayApart) {
  CsvColumns d;
  d.names = {"module0.z", "sensor_module0.force"};
  d.values = {{0.0269873, 0.0269964, 0.027}, {0.70, 0.71, 0.0}};
  d.rows = 3;
  PlotOptions opt;
  opt.x = "module0.z";
  opt.y = {"sensor_module0.force"};
  opt.width = 520;
  cv::Mat img;
  const PlotResult r = RenderPlot(d, opt, &img);
  ASSERT_GE(r.x.ticks.size(), 2u);
  int widest = 0;
  for (const std::string& t : r.x.tick_labels) {
    int baseline = 0;
    widest = std::max(
        widest,
        cv::getTextSize(t, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline).width);
  }
  const double gap = static_cast<double>(r.area.width) / (r.x.ticks.size() - 1);
  EXPECT_LT(widest, gap) << r.x.tick_labels.front();
  // Labels keep all the digits the ticks need, with a common format.
  for (size_t i = 1; i < r.x.tick_labels.size(); ++i) {
    EXPECT_NE(r.x.tick_labels[i], r.x.tick_labels[i - 1]);
    EXPECT_EQ(r.x.tick_labels[i].size(), r.x.tick_labels[0].size());
  }
}

TEST(Plot, CsvToPngWritesADecodableImage) {
  const std::string dir = testing::TempDir("plot_png");
  const std::string csv = dir + "/MRSIM_STATE_snake.csv";
  {
    std::ofstream out(csv);
    out << "time,seq,robot,sensor_module0.force,module0.z\n";
    for (int i = 0; i < 200; ++i) {
      out << 0.001 * i << "," << i << ",snake," << 5 + std::cos(0.05 * i) << ","
          << 0.02 + 0.0001 * i << "\n";
    }
  }
  PlotOptions opt;
  opt.x = "module0.z";
  opt.y = {"sensor_module0.force"};
  opt.title = "front force against height";
  const PlotResult r = PlotCsvToPng(csv, opt, dir + "/force.png");
  const cv::Mat img = cv::imread(dir + "/force.png");
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, opt.width);
  EXPECT_EQ(r.points, 200u);
  EXPECT_LE(r.y.min, 4.0);
  EXPECT_GE(r.y.max, 6.0);
  EXPECT_GT(ColorExtent(img, r.area, r.colors[0]).area(), 1000);
}

TEST(Plot, SeveralCsvsDrawOneCurveEachNamedByTheirRun) {
  const std::string dir = testing::TempDir("plot_runs");
  std::vector<std::string> csvs;
  for (int run = 1; run <= 2; ++run) {
    const std::string folder = dir + "/run" + std::to_string(run);
    std::filesystem::create_directories(folder);
    csvs.push_back(folder + "/generations.csv");
    std::ofstream out(csvs.back());
    out << "generation,best_so_far\n";
    // Run 2 is longer and better: the axes cover both.
    for (int g = 0; g < 10 * run; ++g) out << g << "," << run * 0.1 * g << "\n";
  }
  PlotOptions opt;
  opt.x = "generation";
  opt.y = {"best_so_far"};
  const PlotResult r = PlotCsvsToPng(csvs, opt, dir + "/best.png");
  EXPECT_EQ(r.legend, (std::vector<std::string>{"run1: best_so_far",
                                                "run2: best_so_far"}));
  EXPECT_EQ(r.points, 30u);
  EXPECT_GE(r.x.max, 19.0);
  EXPECT_GE(r.y.max, 3.8);
  const cv::Mat img = cv::imread(dir + "/best.png");
  ASSERT_FALSE(img.empty());
  // Below the legend (top right), which shows both colours.
  const cv::Rect curves(r.area.x, r.area.y + 70, r.area.width,
                        r.area.height - 70);
  const cv::Rect one = ColorExtent(img, curves, r.colors[0]);
  const cv::Rect two = ColorExtent(img, curves, r.colors[1]);
  // Run 1 ends near the middle of x (generation 9 of 19); run 2 goes on
  // towards the right end.
  EXPECT_LT(one.x + one.width, r.area.x + r.area.width * 0.6);
  EXPECT_GT(two.x + two.width, r.area.x + r.area.width * 0.8);
}

TEST(Plot, TheLegendGoesWhereItHidesNoCurve) {
  // A line rising to the top right corner, where the legend used to sit.
  PlotCurve rising{"rising", {0, 1, 2}, {0, 1, 2}};
  PlotOptions opt;
  opt.x = "x";
  opt.y = {"rising"};
  cv::Mat img;
  const PlotResult r = RenderCurves({rising}, opt, &img);
  // The first free corner: top left (the line runs bottom left to top
  // right).
  EXPECT_LT(r.legend_box.x, r.area.x + r.area.width / 2);
  EXPECT_LT(r.legend_box.y, r.area.y + r.area.height / 2);
  // A falling line leaves the top right free: the legend stays there.
  PlotCurve falling{"rising", {0, 1, 2}, {2, 1, 0}};
  const PlotResult f = RenderCurves({falling}, opt, &img);
  EXPECT_GT(f.legend_box.x, f.area.x + f.area.width / 2);
  EXPECT_LT(f.legend_box.y, f.area.y + f.area.height / 2);
}

TEST(Plot, WholeNumbersOnXGetWholeNumberTicks) {
  const PlotAxis fine = NiceAxis(0, 2, 8);
  EXPECT_EQ(fine.tick_labels[1], "0.5");
  const PlotAxis whole = NiceAxis(0, 2, 8, true);
  EXPECT_EQ(whole.tick_labels, (std::vector<std::string>{"0", "1", "2"}));
}

TEST(Plot, DistinctNamesKeepWhatTellsThePathsApart) {
  EXPECT_EQ(DistinctNames({"out/run1/csv/S.csv", "out/run2/csv/S.csv"}),
            (std::vector<std::string>{"run1", "run2"}));
  EXPECT_EQ(DistinctNames({"a.csv", "./b.csv"}),
            (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(DistinctNames({"a.csv", "run/a.csv"}),
            (std::vector<std::string>{"a", "run"}));
}

TEST(Plot, AFolderGivenForTheCsvOrThePngIsSaidToBeOne) {
  const std::string dir = testing::TempDir("plot_folders");
  const std::string csv = dir + "/a.csv";
  { std::ofstream(csv) << "time,v\n0,1\n1,2\n"; }
  PlotOptions opt;
  opt.y = {"v"};
  const auto error = [&](const std::string& in, const std::string& out) {
    try {
      PlotCsvToPng(in, opt, out);
    } catch (const PlotInputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(dir, dir + "/a.png"), dir + ": is a folder, not a CSV file");
  EXPECT_EQ(error(csv, dir), dir +
                                 ": is a folder; expected a PNG file name (-o "
                                 "FOLDER/chart.png)");
  // Other wrong files: a PNG name without .png, a scenario for the CSV.
  EXPECT_EQ(error(csv, dir + "/chart"),
            dir + "/chart: expected a file name ending in .png (e.g. " + dir +
                "/chart.png)");
  const std::string xml = dir + "/worm.xml";
  { std::ofstream(xml) << "<?xml version=\"1.0\"?>\n<Scenario/>\n"; }
  EXPECT_EQ(error(xml, dir + "/a.png"),
            xml +
                ": not a CSV file (expected a header line of column names, "
                "as mrsim-log and mrsim-opt write)");
}

TEST(Plot, CellsThatAreNotNumbersAreLeftOutAndTold) {
  const std::string dir = testing::TempDir("plot_not_numbers");
  const std::string csv = dir + "/a.csv";
  { std::ofstream(csv) << "time,v\n0,1\n1,abc\n2,\n3,4\n"; }
  PlotOptions opt;
  opt.y = {"v"};
  const PlotResult r = PlotCsvToPng(csv, opt, dir + "/a.png");
  EXPECT_EQ(r.points, 2u);
  EXPECT_EQ(r.not_numbers, 1u) << "an empty cell is a missing value";
  EXPECT_EQ(r.first_not_number, csv + ":3: column 'v': 'abc'");
  EXPECT_NE(PlotSummary(r, opt, "a.png")
                .find("note: 1 cell is not a number, left out (first: " + csv +
                      ":3:"),
            std::string::npos)
      << PlotSummary(r, opt, "a.png");
}

TEST(Plot, MissingColumnIsNamedWithTheColumnsThatExist) {
  const std::string dir = testing::TempDir("plot_missing");
  const std::string csv = dir + "/a.csv";
  { std::ofstream(csv) << "time,module0.z\n0,1\n"; }
  PlotOptions opt;
  opt.y = {"module0.zz"};
  try {
    PlotCsvToPng(csv, opt, dir + "/a.png");
    FAIL() << "no error";
  } catch (const PlotInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(csv), std::string::npos) << what;
    EXPECT_NE(what.find("'module0.zz'"), std::string::npos) << what;
    EXPECT_NE(what.find("module0.z"), std::string::npos) << what;
  }
}

TEST(Plot, LogPlotSpecReadsEveryField) {
  const LogPlotSpec s = ParseLogPlotSpec(
      "MRSIM_STATE_snake:x=module0.z:y=sensor_module0.force,"
      "sensor_module1.force:title=Force:style=points:size=640x480:f.png");
  EXPECT_EQ(s.channel, "MRSIM_STATE_snake");
  EXPECT_EQ(s.options.x, "module0.z");
  EXPECT_EQ(s.options.y, (std::vector<std::string>{"sensor_module0.force",
                                                   "sensor_module1.force"}));
  EXPECT_EQ(s.options.title, "Force");
  EXPECT_EQ(s.options.style, PlotOptions::Style::kPoints);
  EXPECT_EQ(s.options.width, 640);
  EXPECT_EQ(s.options.height, 480);
  EXPECT_EQ(s.out, "f.png");
  const LogPlotSpec d = ParseLogPlotSpec("C:y=a");
  EXPECT_EQ(d.options.x, "time");
  EXPECT_EQ(d.out, "C.a.png");
}

TEST(Plot, LogPlotSpecErrorsSayWhatWasExpected) {
  for (const std::string bad :
       {"C", "C:x=time", "C:y=a:colour=red", "C:y=a:size=big", ":y=a",
        "C:y=a:style=bars", "C:y=a,:x=time"}) {
    try {
      ParseLogPlotSpec(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const PlotInputError& e) {
      EXPECT_NE(std::string(e.what()).find("expected CHANNEL:y="),
                std::string::npos)
          << e.what();
    }
  }
  // The channel left out is named as such, not as a missing column.
  try {
    ParseLogPlotSpec("y=com.x");
    ADD_FAILURE() << "accepted";
  } catch (const PlotInputError& e) {
    EXPECT_NE(std::string(e.what()).find("no channel before 'y=com.x'"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mrsim
