// mrsim-plot: draws a PNG chart from a CSV written by mrsim-log.
#include <cstdio>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "common/cli_exit.h"
#include "common/version.h"
#include "logger/plot.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Draws columns of a mrsim-log CSV against time or against another "
      "column, as a PNG with axes, ticks, units, legend and title."};
  app.set_version_flag("--version",
                       std::string("mrsim-plot ") + mrsim::kVersion);
  std::vector<std::string> csvs;
  std::string out, style = "auto";
  mrsim::PlotOptions options;
  app.add_option("csv", csvs,
                 "CSV file(s) written by mrsim-log or mrsim-opt; several "
                 "draw each y column of each on one chart")
      ->required();
  app.add_option("--x", options.x, "column on the x axis")
      ->capture_default_str();
  app.add_option("--y", options.y, "column(s) on the y axis (repeatable)")
      ->required();
  app.add_option("--title", options.title,
                 "chart title (default: '<y> against <x>')");
  app.add_option("--x-label", options.x_label,
                 "x axis label (default: column and unit)");
  app.add_option("--y-label", options.y_label,
                 "y axis label (default: column and unit)");
  app.add_option("--width", options.width, "image width (px)")
      ->capture_default_str();
  app.add_option("--height", options.height, "image height (px)")
      ->capture_default_str();
  app.add_option("--style", style,
                 "auto (lines for time series, else points), lines, points")
      ->capture_default_str();
  app.add_option("-o,--out", out, "PNG file to write")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    options.style = mrsim::ParsePlotStyle(style);
    const mrsim::PlotResult r = mrsim::PlotCsvsToPng(csvs, options, out);
    std::fputs(mrsim::PlotSummary(r, options, out).c_str(), stdout);
    return 0;
  } catch (const mrsim::PlotInputError& e) {
    std::fprintf(stderr, "mrsim-plot: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-plot: error: %s\n", e.what());
    return 1;
  }
}
