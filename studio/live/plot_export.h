// A live plot written as a PNG with the logger's plot code, so a plot
// exported from the window looks like one mrsim-log --plot draws.
#pragma once

#include <string>

#include "logger/plot.h"
#include "studio/live/plot_series.h"

namespace mrsim::studio {

// Draws what `series` holds now (its column against time). Throws
// PlotInputError when it holds no point, std::runtime_error naming the PNG
// when it cannot be written.
PlotResult ExportPlotPng(const PlotSeries& series, const std::string& png_path);

}  // namespace mrsim::studio
