// PNG charts from logger CSVs, drawn with OpenCV: chosen columns against
// time or against another column, with axes, ticks, tick labels, axis
// labels with units, a legend and a title.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "logger/csv_columns.h"

namespace mrsim {

struct PlotOptions {
  std::string x = "time";
  std::vector<std::string> y;
  std::string title;    // empty: "<y> against <x>"
  std::string x_label;  // empty: column name and unit
  std::string y_label;
  int width = 960;
  int height = 600;
  // kAuto draws lines when x never decreases (a time series) and points
  // otherwise (one column against another).
  enum class Style { kAuto, kLines, kPoints };
  Style style = Style::kAuto;
};

// One axis as drawn: its range (the data's, rounded out to ticks), the
// ticks and their labels.
struct PlotAxis {
  double min = 0;
  double max = 1;
  double data_min = 0;
  double data_max = 0;
  std::vector<double> ticks;
  std::vector<std::string> tick_labels;
  std::string label;
};

// What RenderPlot drew, so callers and tests can check it.
struct PlotResult {
  PlotAxis x;
  PlotAxis y;
  cv::Rect area;  // the plot area in pixels (inside the axes)
  std::vector<std::string> legend;
  cv::Rect legend_box;  // in pixels; the corner hiding the fewest points
  std::vector<cv::Scalar> colors;  // BGR, one per y column
  std::string title;
  size_t points = 0;             // finite (x, y) pairs drawn
  size_t not_numbers = 0;        // CSV cells left out: not numbers
  std::string first_not_number;  // "FILE:LINE: column 'c': 'text'"
  bool lines = true;
};

// Draws the y columns of `data` against its x column. Throws PlotInputError
// when a column is missing or has no finite value, or the size is too small.
PlotResult RenderPlot(const CsvColumns& data, const PlotOptions& options,
                      cv::Mat* image);

// One curve: its legend entry and its points.
struct PlotCurve {
  std::string name;
  std::vector<double> x, y;
};
// Draws curves that need not share their x values (e.g. the same column of
// several runs); options.x and options.y name the axes and the default
// title. Throws PlotInputError as RenderPlot does.
PlotResult RenderCurves(const std::vector<PlotCurve>& curves,
                        const PlotOptions& options, cv::Mat* image);

// Reads the needed columns of `csv_path`, draws them and writes `png_path`.
// Throws PlotInputError for bad input, std::runtime_error naming the PNG
// when it cannot be written.
PlotResult PlotCsvToPng(const std::string& csv_path, const PlotOptions& options,
                        const std::string& png_path);
// The same over several CSVs (runs to compare) on one chart: each y column
// of each file is a curve, named by what tells the files apart ("run1:
// fitness_best" for out/run1/generations.csv and out/run2/...).
PlotResult PlotCsvsToPng(const std::vector<std::string>& csv_paths,
                         const PlotOptions& options,
                         const std::string& png_path);

// What mrsim-plot says after writing `png_path`: points and ranges, and a
// second line about cells that were not numbers when there were any.
std::string PlotSummary(const PlotResult& result, const PlotOptions& options,
                        const std::string& png_path);

// What tells each path apart from the others: the path components they do
// not all share, without a .csv ending ("run1", "run2"); the whole path
// when nothing is left.
std::vector<std::string> DistinctNames(const std::vector<std::string>& paths);

// Tick positions 1, 2 or 5 times a power of ten covering [lo, hi]; at
// least 1 apart when `integers` (a generation or a count has no 0.5).
PlotAxis NiceAxis(double lo, double hi, int max_ticks = 8,
                  bool integers = false);

// Parses "auto", "lines" or "points".
PlotOptions::Style ParsePlotStyle(const std::string& text);

}  // namespace mrsim
