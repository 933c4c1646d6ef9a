// For tests and tools: where the studio's widgets and parts are on screen
// and what is selected, written to a text file (--layout-dump) whenever it
// changes, so an X test can click real buttons by name.
#pragma once

#include <map>
#include <string>

namespace mrsim::studio {

class LayoutRecorder {
 public:
  explicit LayoutRecorder(std::string path) : path_(std::move(path)) {}
  bool enabled() const { return !path_.empty(); }

  // Called once per frame before widgets are recorded.
  void BeginFrame() { lines_.clear(); }
  // One line "<kind> <name>\t<x> <y> <w> <h>" (window pixels, top left).
  void Widget(const std::string& name, float x, float y, float w, float h);
  // Any other "key\tvalue" line.
  void State(const std::string& key, const std::string& value);
  // Writes the file (atomically) when the content changed.
  void EndFrame();

 private:
  std::string path_;
  std::map<std::string, std::string> lines_;
  std::string written_;
};

}  // namespace mrsim::studio
