#include "studio/live/plot_export.h"

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "logger/csv_columns.h"

namespace mrsim::studio {

PlotResult ExportPlotPng(const PlotSeries& series,
                         const std::string& png_path) {
  if (series.values().empty()) {
    throw PlotInputError("plot " + series.column() + ": no values yet");
  }
  CsvColumns data;
  data.names = {"time", series.column()};
  data.values = {{series.times().begin(), series.times().end()},
                 {series.values().begin(), series.values().end()}};
  data.rows = series.values().size();
  PlotOptions options;
  options.y = {series.column()};
  options.title = series.column() + " (" + series.channel() + ")";
  cv::Mat image;
  const PlotResult result = RenderPlot(data, options, &image);
  if (!cv::imwrite(png_path, image)) {
    throw std::runtime_error("cannot write " + png_path);
  }
  return result;
}

}  // namespace mrsim::studio
