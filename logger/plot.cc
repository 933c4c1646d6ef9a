#include "logger/plot.h"

#include <fmt/format.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "logger/column_units.h"

namespace mrsim {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kGrid(225, 225, 225);

// Distinct, print-friendly colours (BGR).
const cv::Scalar kPalette[] = {{180, 119, 31},  {14, 127, 255},  {44, 160, 44},
                               {40, 39, 214},   {189, 103, 148}, {75, 86, 140},
                               {194, 119, 227}, {34, 189, 188}};

double NiceStep(double raw) {
  const double exp = std::floor(std::log10(raw));
  const double base = std::pow(10.0, exp);
  const double f = raw / base;
  const double nice = f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10;
  return nice * base;
}

// One format for a whole axis (`mag` is its largest |value|): fixed
// decimals for ordinary magnitudes, else scientific; either way enough
// digits to tell neighbouring ticks apart.
std::string TickLabel(double v, double step, double mag) {
  if (std::abs(v) < step * 1e-9) v = 0;
  char buf[48];
  if (mag < 1e7 && mag >= 1e-3) {
    const int decimals = std::clamp(
        static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 15);
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  } else {
    const int digits = std::clamp(
        static_cast<int>(std::ceil(std::log10(mag / step) - 1e-9)), 0, 15);
    std::snprintf(buf, sizeof(buf), "%.*e", digits, v);
  }
  return buf;
}

cv::Size TextSize(const std::string& text, double scale, int thickness) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, thickness, &baseline);
}

}  // namespace

PlotAxis NiceAxis(double lo, double hi, int max_ticks, bool integers) {
  PlotAxis axis;
  axis.data_min = lo;
  axis.data_max = hi;
  if (!(hi > lo)) {
    const double pad = lo == 0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  double step = NiceStep((hi - lo) / std::max(2, max_ticks - 1));
  if (integers) step = std::max(step, 1.0);
  axis.min = std::floor(lo / step) * step;
  axis.max = std::ceil(hi / step) * step;
  while ((axis.max - axis.min) / step > max_ticks) {
    step = NiceStep(step * 1.5);
    axis.min = std::floor(lo / step) * step;
    axis.max = std::ceil(hi / step) * step;
  }
  const int n = static_cast<int>(std::lround((axis.max - axis.min) / step));
  const double mag = std::max(std::abs(axis.min), std::abs(axis.max));
  for (int i = 0; i <= n; ++i) {
    const double t = axis.min + i * step;
    axis.ticks.push_back(t);
    axis.tick_labels.push_back(TickLabel(t, step, mag));
  }
  return axis;
}

PlotOptions::Style ParsePlotStyle(const std::string& text) {
  if (text == "auto") return PlotOptions::Style::kAuto;
  if (text == "lines") return PlotOptions::Style::kLines;
  if (text == "points") return PlotOptions::Style::kPoints;
  throw PlotInputError("plot style '" + text +
                       "': expected auto, lines or points");
}

PlotResult RenderPlot(const CsvColumns& data, const PlotOptions& options,
                      cv::Mat* image) {
  if (options.y.empty()) throw PlotInputError("no y column to plot");
  auto column = [&data](const std::string& name) -> const std::vector<double>& {
    for (size_t i = 0; i < data.names.size(); ++i) {
      if (data.names[i] == name) return data.values[i];
    }
    throw PlotInputError("no column '" + name + "' in the plot data");
  };
  std::vector<PlotCurve> series;
  for (const std::string& y : options.y) {
    series.push_back({y, column(options.x), column(y)});
  }
  return RenderCurves(series, options, image);
}

PlotResult RenderCurves(const std::vector<PlotCurve>& series,
                        const PlotOptions& options, cv::Mat* image) {
  if (options.width < 200 || options.height < 150) {
    throw PlotInputError("plot size " + std::to_string(options.width) + "x" +
                         std::to_string(options.height) +
                         " is too small (at least 200x150)");
  }
  if (series.empty() || options.y.empty()) {
    throw PlotInputError("no y column to plot");
  }

  PlotResult r;
  double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
  bool monotonic = true;
  for (const PlotCurve& c : series) {
    const std::vector<double>& xs = c.x;
    const std::vector<double>& ys = c.y;
    size_t finite = 0;
    for (size_t i = 0; i < ys.size() && i < xs.size(); ++i) {
      if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
      ++finite;
      xlo = std::min(xlo, xs[i]);
      xhi = std::max(xhi, xs[i]);
      ylo = std::min(ylo, ys[i]);
      yhi = std::max(yhi, ys[i]);
    }
    if (finite == 0) {
      throw PlotInputError("column '" + c.name + "' against '" + options.x +
                           "' has no finite values to plot");
    }
    r.points += finite;
    double prev_x = -INFINITY;
    for (double x : xs) {
      if (!std::isfinite(x)) continue;
      if (x < prev_x) monotonic = false;
      prev_x = x;
    }
  }
  // Whole numbers only on x (generations, counts): whole-number ticks.
  bool integer_x = true;
  for (const PlotCurve& c : series) {
    for (double x : c.x) {
      if (std::isfinite(x) && x != std::floor(x)) integer_x = false;
    }
  }
  r.lines = options.style == PlotOptions::Style::kLines ||
            (options.style == PlotOptions::Style::kAuto && monotonic);

  r.y = NiceAxis(ylo, yhi, 8);
  if (!options.y_label.empty()) {
    r.y.label = options.y_label;
  } else if (options.y.size() == 1) {
    r.y.label = ColumnLabel(options.y[0]);
  } else {
    const std::string unit = ColumnUnit(options.y[0]);
    const bool same = std::all_of(
        options.y.begin(), options.y.end(),
        [&unit](const std::string& c) { return ColumnUnit(c) == unit; });
    r.y.label = same && !unit.empty() ? "value [" + unit + "]" : "value";
  }
  if (!options.title.empty()) {
    r.title = options.title;
  } else {
    std::string ys;
    for (const std::string& y : options.y) ys += (ys.empty() ? "" : ", ") + y;
    r.title = ys + " against " + options.x;
  }

  // Layout: room for tick labels and the rotated y label on the left; as
  // many x ticks as fit without their labels touching.
  int widest_tick = 0;
  for (const std::string& t : r.y.tick_labels) {
    widest_tick = std::max(widest_tick, TextSize(t, 0.45, 1).width);
  }
  const int left = 30 + widest_tick + 16;
  const int top = 48;
  const int bottom = 64;
  int right = 24;
  for (int max_ticks = 9; max_ticks >= 2; --max_ticks) {
    r.x = NiceAxis(xlo, xhi, max_ticks, integer_x);
    int widest = 0;
    for (const std::string& t : r.x.tick_labels) {
      widest = std::max(widest, TextSize(t, 0.45, 1).width);
    }
    right =
        std::max(24, TextSize(r.x.tick_labels.back(), 0.45, 1).width / 2 + 6);
    const int width = options.width - left - right;
    const int gap = r.x.ticks.size() > 1
                        ? width / static_cast<int>(r.x.ticks.size() - 1)
                        : width;
    if (widest + 12 <= gap) break;
  }
  r.x.label =
      options.x_label.empty() ? ColumnLabel(options.x) : options.x_label;
  r.area = cv::Rect(left, top, options.width - left - right,
                    options.height - top - bottom);
  if (r.area.width < 50 || r.area.height < 50) {
    throw PlotInputError("plot size too small for its labels");
  }

  cv::Mat img(options.height, options.width, CV_8UC3, kWhite);
  const cv::Rect& a = r.area;
  auto px = [&](double v) {
    return a.x + static_cast<int>(std::lround((v - r.x.min) /
                                              (r.x.max - r.x.min) * a.width));
  };
  auto py = [&](double v) {
    return a.y + a.height -
           static_cast<int>(
               std::lround((v - r.y.min) / (r.y.max - r.y.min) * a.height));
  };

  // Grid, ticks and tick labels.
  for (size_t i = 0; i < r.x.ticks.size(); ++i) {
    const int x = px(r.x.ticks[i]);
    cv::line(img, {x, a.y}, {x, a.y + a.height}, kGrid, 1);
    cv::line(img, {x, a.y + a.height}, {x, a.y + a.height + 6}, kBlack, 1);
    const cv::Size s = TextSize(r.x.tick_labels[i], 0.45, 1);
    cv::putText(img, r.x.tick_labels[i], {x - s.width / 2, a.y + a.height + 22},
                kFont, 0.45, kBlack, 1, cv::LINE_AA);
  }
  for (size_t i = 0; i < r.y.ticks.size(); ++i) {
    const int y = py(r.y.ticks[i]);
    cv::line(img, {a.x, y}, {a.x + a.width, y}, kGrid, 1);
    cv::line(img, {a.x - 6, y}, {a.x, y}, kBlack, 1);
    const cv::Size s = TextSize(r.y.tick_labels[i], 0.45, 1);
    cv::putText(img, r.y.tick_labels[i], {a.x - 10 - s.width, y + s.height / 2},
                kFont, 0.45, kBlack, 1, cv::LINE_AA);
  }

  // Data, clipped to the plot area.
  cv::Mat plot_area = img(a);
  const cv::Point offset(a.x, a.y);
  for (size_t k = 0; k < series.size(); ++k) {
    const cv::Scalar color =
        kPalette[k % (sizeof(kPalette) / sizeof(kPalette[0]))];
    r.colors.push_back(color);
    r.legend.push_back(series[k].name);
    const std::vector<double>& xs = series[k].x;
    const std::vector<double>& ys = series[k].y;
    std::vector<cv::Point> run;
    auto flush = [&] {
      if (run.size() > 1) {
        cv::polylines(plot_area, run, false, color, 2, cv::LINE_AA);
      } else if (run.size() == 1) {
        cv::circle(plot_area, run[0], 2, color, cv::FILLED, cv::LINE_AA);
      }
      run.clear();
    };
    for (size_t i = 0; i < ys.size() && i < xs.size(); ++i) {
      if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
        if (r.lines) flush();
        continue;
      }
      const cv::Point p(px(xs[i]), py(ys[i]));
      if (r.lines) {
        if (run.empty() || run.back() != p - offset) run.push_back(p - offset);
      } else {
        cv::circle(plot_area, p - offset, 2, color, cv::FILLED, cv::LINE_AA);
      }
    }
    if (r.lines) flush();
  }

  // Axes on top of the data.
  cv::line(img, {a.x, a.y + a.height}, {a.x + a.width, a.y + a.height}, kBlack,
           1);
  cv::line(img, {a.x, a.y}, {a.x, a.y + a.height}, kBlack, 1);

  // Axis labels; the y label is drawn sideways.
  {
    const cv::Size s = TextSize(r.x.label, 0.55, 1);
    cv::putText(img, r.x.label,
                {a.x + (a.width - s.width) / 2, options.height - 14}, kFont,
                0.55, kBlack, 1, cv::LINE_AA);
  }
  {
    const cv::Size s = TextSize(r.y.label, 0.55, 1);
    const int w = std::min(s.width + 4, a.height);
    cv::Mat label(s.height + 8, w, CV_8UC3, kWhite);
    cv::putText(label, r.y.label, {2, s.height + 2}, kFont, 0.55, kBlack, 1,
                cv::LINE_AA);
    cv::Mat rotated;
    cv::rotate(label, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int y0 = a.y + (a.height - rotated.rows) / 2;
    rotated.copyTo(img(cv::Rect(6, y0, rotated.cols, rotated.rows)));
  }
  {
    const cv::Size s = TextSize(r.title, 0.7, 2);
    cv::putText(img, r.title, {std::max(4, (options.width - s.width) / 2), 32},
                kFont, 0.7, kBlack, 2, cv::LINE_AA);
  }

  // Legend in the corner of the plot area that hides the fewest points
  // (top right when none is better): a rising curve ends top right.
  int legend_w = 0;
  for (const std::string& name : r.legend) {
    legend_w = std::max(legend_w, TextSize(name, 0.45, 1).width);
  }
  legend_w += 50;
  const int row_h = 20;
  const int legend_h = row_h * static_cast<int>(r.legend.size()) + 8;
  const int right_x = a.x + a.width - legend_w - 8;
  const int bottom_y = a.y + a.height - legend_h - 8;
  cv::Rect box(right_x, a.y + 8, legend_w, legend_h);
  size_t fewest = SIZE_MAX;
  for (const cv::Point& corner :
       {cv::Point(right_x, a.y + 8), cv::Point(a.x + 8, a.y + 8),
        cv::Point(right_x, bottom_y), cv::Point(a.x + 8, bottom_y)}) {
    const cv::Rect candidate(corner.x, corner.y, legend_w, legend_h);
    // Points, and with lines every few pixels along each segment.
    size_t hidden = 0;
    for (const PlotCurve& c : series) {
      cv::Point2d last;
      bool have_last = false;
      for (size_t i = 0; i < c.x.size() && i < c.y.size(); ++i) {
        if (!std::isfinite(c.x[i]) || !std::isfinite(c.y[i])) {
          have_last = false;
          continue;
        }
        const cv::Point2d p(px(c.x[i]), py(c.y[i]));
        const int steps =
            r.lines && have_last
                ? std::max(1, static_cast<int>(cv::norm(p - last) / 4))
                : 1;
        for (int k = 1; k <= steps; ++k) {
          const cv::Point2d q = have_last && r.lines
                                    ? last + (p - last) * (double(k) / steps)
                                    : p;
          if (candidate.contains(cv::Point(q))) ++hidden;
        }
        last = p;
        have_last = true;
      }
    }
    if (hidden < fewest) fewest = hidden, box = candidate;
  }
  r.legend_box = box;
  if (box.x > a.x) {
    cv::rectangle(img, box, kWhite, cv::FILLED);
    cv::rectangle(img, box, kBlack, 1);
    for (size_t k = 0; k < r.legend.size(); ++k) {
      const int y = box.y + 14 + row_h * static_cast<int>(k);
      if (r.lines) {
        cv::line(img, {box.x + 8, y}, {box.x + 34, y}, r.colors[k], 2,
                 cv::LINE_AA);
      } else {
        for (int x : {box.x + 12, box.x + 21, box.x + 30}) {
          cv::circle(img, {x, y}, 2, r.colors[k], cv::FILLED, cv::LINE_AA);
        }
      }
      cv::putText(img, r.legend[k], {box.x + 40, y + 5}, kFont, 0.45, kBlack, 1,
                  cv::LINE_AA);
    }
  }
  *image = img;
  return r;
}

namespace {

void WritePng(const cv::Mat& image, const std::string& png_path) {
  std::error_code ec;
  if (std::filesystem::is_directory(png_path, ec)) {
    throw PlotInputError(png_path +
                         ": is a folder; expected a PNG file name (-o "
                         "FOLDER/chart.png)");
  }
  std::string extension = std::filesystem::path(png_path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(c));
  if (extension != ".png") {
    throw PlotInputError(
        png_path + ": expected a file name ending in .png (e.g. " +
        std::filesystem::path(png_path).replace_extension(".png").string() +
        ")");
  }
  // stb's PNG writer rather than OpenCV's imgcodecs, whose hundred-odd
  // libraries (GDAL, Poppler, ...) cost mrsim-log some 80 ms of CPU at
  // every start, what it spends on a third of a second of a 1 kHz robot
  // state (bench/mcap_logger).
  cv::Mat rgb;
  cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
  const int ok = stbi_write_png(png_path.c_str(), rgb.cols, rgb.rows, 3,
                                rgb.data, static_cast<int>(rgb.step));
  if (ok == 0) {
    throw std::runtime_error("cannot write plot " + png_path +
                             " (is the folder there and writable?)");
  }
}

std::vector<std::string> WantedColumns(const PlotOptions& options) {
  std::vector<std::string> wanted = {options.x};
  for (const std::string& y : options.y) {
    if (std::find(wanted.begin(), wanted.end(), y) == wanted.end()) {
      wanted.push_back(y);
    }
  }
  return wanted;
}

}  // namespace

PlotResult PlotCsvToPng(const std::string& csv_path, const PlotOptions& options,
                        const std::string& png_path) {
  const CsvColumns data = ReadCsvColumns(csv_path, WantedColumns(options));
  cv::Mat image;
  PlotResult r;
  try {
    r = RenderPlot(data, options, &image);
  } catch (const PlotInputError& e) {
    throw PlotInputError(csv_path + ": " + e.what());
  }
  r.not_numbers = data.not_numbers;
  r.first_not_number = data.first_not_number;
  WritePng(image, png_path);
  return r;
}

PlotResult PlotCsvsToPng(const std::vector<std::string>& csv_paths,
                         const PlotOptions& options,
                         const std::string& png_path) {
  if (csv_paths.size() == 1) {
    return PlotCsvToPng(csv_paths[0], options, png_path);
  }
  const std::vector<std::string> names = DistinctNames(csv_paths);
  std::vector<PlotCurve> series;
  size_t not_numbers = 0;
  std::string first_not_number;
  for (size_t f = 0; f < csv_paths.size(); ++f) {
    const CsvColumns data =
        ReadCsvColumns(csv_paths[f], WantedColumns(options));
    if (not_numbers == 0) first_not_number = data.first_not_number;
    not_numbers += data.not_numbers;
    // ReadCsvColumns returns the wanted columns in order: x first.
    for (const std::string& y : options.y) {
      const size_t i = static_cast<size_t>(
          std::find(data.names.begin(), data.names.end(), y) -
          data.names.begin());
      series.push_back(
          {names[f] + ": " + y, data.values.front(), data.values.at(i)});
    }
  }
  cv::Mat image;
  // An error names the curve, and so the file.
  PlotResult r = RenderCurves(series, options, &image);
  r.not_numbers = not_numbers;
  r.first_not_number = first_not_number;
  WritePng(image, png_path);
  return r;
}

std::string PlotSummary(const PlotResult& r, const PlotOptions& options,
                        const std::string& png_path) {
  std::string text = fmt::format(
      "mrsim-plot: wrote {}: {} points, x {} in [{:g}, {:g}], y in [{:g}, "
      "{:g}]\n",
      png_path, r.points, options.x, r.x.data_min, r.x.data_max, r.y.data_min,
      r.y.data_max);
  if (r.not_numbers > 0) {
    text += fmt::format(
        "mrsim-plot: note: {} cell{} not a number, left out (first: {})\n",
        r.not_numbers, r.not_numbers == 1 ? " is" : "s are",
        r.first_not_number);
  }
  return text;
}

std::vector<std::string> DistinctNames(const std::vector<std::string>& paths) {
  std::vector<std::vector<std::string>> parts;
  for (const std::string& p : paths) {
    std::vector<std::string> c;
    for (const auto& e : std::filesystem::path(p).lexically_normal()) {
      c.push_back(e.string());
    }
    if (!c.empty() && c.back().size() > 4 &&
        c.back().compare(c.back().size() - 4, 4, ".csv") == 0) {
      c.back().resize(c.back().size() - 4);
    }
    parts.push_back(c);
  }
  size_t shortest = parts.front().size();
  for (const auto& c : parts) shortest = std::min(shortest, c.size());
  const auto all_share = [&](auto component_of) {
    for (const auto& c : parts) {
      if (component_of(c) != component_of(parts.front())) return false;
    }
    return true;
  };
  size_t head = 0, tail = 0;
  while (head + tail < shortest &&
         all_share([&](const auto& c) { return c[head]; })) {
    ++head;
  }
  while (head + tail < shortest &&
         all_share([&](const auto& c) { return c[c.size() - 1 - tail]; })) {
    ++tail;
  }
  std::vector<std::string> names;
  for (const auto& c : parts) {
    std::string name;
    for (size_t i = head; i + tail < c.size(); ++i) {
      name += (name.empty() ? "" : "/") + c[i];
    }
    if (name.empty()) {  // a path inside another's folders: all of it
      for (const std::string& e : c) name += (name.empty() ? "" : "/") + e;
    }
    names.push_back(name);
  }
  return names;
}

}  // namespace mrsim
