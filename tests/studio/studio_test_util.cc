#include "tests/studio/studio_test_util.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace mrsim::testing {

XvfbDisplay::XvfbDisplay(const std::string& dir) {
  const std::string log = dir + "/xvfb.log";
  // -displayfd: Xvfb picks a free display and writes its number once it
  // accepts connections.
  server_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/bin/Xvfb", "-displayfd", "1", "-screen",
                               "0", "1280x800x24", "-nolisten", "tcp"},
      log);
  WaitUntil(
      [&] {
        std::ifstream in(log);
        std::string line;
        while (std::getline(in, line)) {
          if (!line.empty() &&
              line.find_first_not_of("0123456789") == std::string::npos) {
            display_ = ":" + line;
            return true;
          }
        }
        return !server_->running();
      },
      60);
  if (!display_.empty()) setenv("DISPLAY", display_.c_str(), 1);
}

std::map<std::string, std::string> ReadLayout(const std::string& path) {
  std::map<std::string, std::string> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const size_t tab = line.find('\t');
    if (tab != std::string::npos)
      out[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return out;
}

bool WaitForLayout(const std::string& layout, const std::string& key,
                   const std::string& value, double timeout_s) {
  return WaitUntil(
      [&] {
        const auto l = ReadLayout(layout);
        auto it = l.find(key);
        return it != l.end() && it->second == value;
      },
      timeout_s);
}

bool WidgetCentre(const std::string& layout, const std::string& name, int* x,
                  int* y) {
  const auto l = ReadLayout(layout);
  auto it = l.find("widget " + name);
  if (it == l.end()) return false;
  std::istringstream in(it->second);
  int left, top, w, h;
  if (!(in >> left >> top >> w >> h)) return false;
  *x = left + w / 2;
  *y = top + h / 2;
  return true;
}

bool Xdotool(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {"/usr/bin/xdotool"};
  argv.insert(argv.end(), args.begin(), args.end());
  ChildProcess tool(argv);
  return tool.Wait(30) == 0;
}

bool ClickAt(int x, int y) {
  return Xdotool(
      {"mousemove", std::to_string(x), std::to_string(y), "click", "1"});
}

bool ClickWhenThere(const std::string& layout, int x, int y) {
  const std::string xs = std::to_string(x), ys = std::to_string(y);
  return Xdotool({"mousemove", xs, ys}) &&
         WaitForLayout(layout, "mouse", xs + " " + ys) &&
         Xdotool({"click", "1"});
}

bool DragOnScreen(const std::string& layout, int x0, int y0, int x1, int y1,
                  const std::string& key, const std::string& started) {
  auto xy = [](int x, int y) {
    return std::to_string(x) + " " + std::to_string(y);
  };
  if (!Xdotool({"mousemove", std::to_string(x0), std::to_string(y0)}) ||
      !WaitForLayout(layout, "mouse", xy(x0, y0)) ||
      !Xdotool({"mousedown", "1"}) ||
      !WaitForLayout(layout, "mouse", xy(x0, y0) + " down")) {
    return false;
  }
  // Past ImGui's drag threshold, towards the target.
  const int sx = x0 + (x1 > x0 ? 12 : x1 < x0 ? -12 : 0);
  const int sy = y0 + (y1 > y0 ? 12 : y1 < y0 ? -12 : 0);
  return Xdotool({"mousemove", std::to_string(sx), std::to_string(sy)}) &&
         WaitForLayout(layout, key, started) &&
         Xdotool({"mousemove", std::to_string(x1), std::to_string(y1)}) &&
         WaitForLayout(layout, "mouse", xy(x1, y1) + " down") &&
         Xdotool({"mouseup", "1"});
}

}  // namespace mrsim::testing
