#include "logger/log_plot_spec.h"

#include <cstdio>
#include <vector>

namespace mrsim {
namespace {

std::vector<std::string> Split(const std::string& text, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t end = text.find(sep, start);
    out.push_back(text.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

LogPlotSpec ParseLogPlotSpec(const std::string& text) {
  auto fail = [&text](const std::string& what) -> PlotInputError {
    return PlotInputError(
        "--plot '" + text + "': " + what +
        " (expected CHANNEL:y=COL[,COL...][:x=COL][:title=TEXT]"
        "[:style=auto|lines|points][:size=WxH][:out=FILE.png])");
  };
  const std::vector<std::string> fields = Split(text, ':');
  LogPlotSpec spec;
  spec.channel = fields[0];
  if (spec.channel.empty()) throw fail("no channel");
  if (spec.channel.find('=') != std::string::npos) {
    // "y=com.x" alone: the channel was left out, not the column.
    throw fail("no channel before '" + spec.channel +
               "' (e.g. MRSIM_STATE_snake:" + spec.channel + ")");
  }
  for (size_t i = 1; i < fields.size(); ++i) {
    const std::string& f = fields[i];
    const size_t eq = f.find('=');
    if (eq == std::string::npos) {
      if (i + 1 == fields.size() && f.size() > 4 &&
          f.substr(f.size() - 4) == ".png") {
        spec.out = f;
        continue;
      }
      throw fail("field '" + f + "' is not key=value");
    }
    const std::string key = f.substr(0, eq);
    const std::string value = f.substr(eq + 1);
    if (key == "x") {
      if (value.empty()) throw fail("empty x");
      spec.options.x = value;
    } else if (key == "y") {
      for (const std::string& y : Split(value, ',')) {
        if (y.empty()) throw fail("empty y column");
        spec.options.y.push_back(y);
      }
    } else if (key == "title") {
      spec.options.title = value;
    } else if (key == "style") {
      try {
        spec.options.style = ParsePlotStyle(value);
      } catch (const PlotInputError& e) {
        throw fail(e.what());
      }
    } else if (key == "size") {
      int w = 0, h = 0;
      char extra = 0;
      if (std::sscanf(value.c_str(), "%dx%d%c", &w, &h, &extra) != 2) {
        throw fail("size '" + value + "' is not WxH");
      }
      spec.options.width = w;
      spec.options.height = h;
    } else if (key == "out") {
      spec.out = value;
    } else {
      throw fail("unknown key '" + key + "'");
    }
  }
  if (spec.options.y.empty()) throw fail("no y=COLUMN");
  if (spec.out.empty())
    spec.out = spec.channel + "." + spec.options.y[0] + ".png";
  return spec;
}

}  // namespace mrsim
