// The --plot option of mrsim-log: which chart to draw from which channel's
// CSV when logging stops. Format (fields separated by ':'):
//   CHANNEL:y=COL[,COL...][:x=COL][:title=TEXT][:style=auto|lines|points]
//          [:size=WxH][:out=FILE.png | :FILE.png]
// x defaults to time; out defaults to <CHANNEL>.<first y>.png; a relative
// out is inside the --out folder.
#pragma once

#include <string>

#include "logger/plot.h"

namespace mrsim {

struct LogPlotSpec {
  std::string channel;
  PlotOptions options;
  std::string out;  // as given, possibly relative
};

// Throws PlotInputError naming the spec and what was expected.
LogPlotSpec ParseLogPlotSpec(const std::string& text);

}  // namespace mrsim
