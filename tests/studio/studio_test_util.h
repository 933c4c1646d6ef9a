// For the studio's window tests: a private Xvfb display per test, the
// studio's --layout-dump file, and real X input through xdotool.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"

namespace mrsim::testing {

// An Xvfb server on a free display number (Xvfb picks it: -displayfd),
// ready when the constructor returns; DISPLAY is set for child processes.
class XvfbDisplay {
 public:
  explicit XvfbDisplay(const std::string& dir);
  bool ok() const { return !display_.empty(); }
  const std::string& display() const { return display_; }

 private:
  std::unique_ptr<ChildProcess> server_;
  std::string display_;
};

// The studio's --layout-dump file as key -> value.
std::map<std::string, std::string> ReadLayout(const std::string& path);

// Waits until the layout file has `key` equal to `value`.
bool WaitForLayout(const std::string& layout, const std::string& key,
                   const std::string& value, double timeout_s = 90);

// The centre of widget `name` ("widget <name>" line) in window pixels.
bool WidgetCentre(const std::string& layout, const std::string& name, int* x,
                  int* y);

// Runs xdotool with `args` on the current DISPLAY; true on exit code 0.
bool Xdotool(const std::vector<std::string>& args);
// Moves the pointer to (x, y) and clicks the left button.
bool ClickAt(int x, int y);
// Moves the pointer to (x, y), waits until the window has drawn a frame
// with the mouse there (the layout's "mouse" line), then clicks: a click
// is never taken for one at the pointer's previous place.
bool ClickWhenThere(const std::string& layout, int x, int y);
// Presses at (x0, y0), moves a little until the studio reports `key` ==
// `started`, moves to (x1, y1) and releases there. Every step waits until
// the window has seen it (the layout's "mouse" line); false at the first
// step that does not happen.
bool DragOnScreen(const std::string& layout, int x0, int y0, int x1, int y1,
                  const std::string& key, const std::string& started);

}  // namespace mrsim::testing
