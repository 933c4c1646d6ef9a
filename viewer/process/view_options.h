// Command-line options of mrsim-view, parsed with CLI11.
#pragma once

#include <cstdint>
#include <string>

#include "viewer/state_viewer.h"

namespace mrsim {

struct ViewOptions {
  std::string scenario;
  std::string lcm_url;  // empty: LCM's default
  std::string prefix = "MRSIM";
  std::string from_log;    // .lcmlog to replay instead of listening
  std::string out;         // MP4 path
  std::string frames_dir;  // PNG folder
  double fps = 30.0;
  bool window = false;
  int64_t max_frames = 0;  // 0: until stopped or the log ends
  int queue = 8;           // newest states kept per robot (older ones drop)
  ViewerOptions viewer;    // quality.shadow_size defaults to 1024 here

  ViewOptions() { viewer.quality.shadow_size = kDefaultShadowSize; }
  // MuJoCo's 4096 shadow map makes software rendering several times slower
  // for little visible gain at video sizes.
  static constexpr int kDefaultShadowSize = 1024;
};

// Parses argv. Returns -1 to go on, or an exit code: 0 after --help, 2 on
// bad flags (the message is printed).
int ParseViewOptions(int argc, char** argv, ViewOptions* options);

}  // namespace mrsim
