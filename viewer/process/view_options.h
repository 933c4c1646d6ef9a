// Command-line options of mrsim-view, parsed with CLI11.
#pragma once

#include <cstdint>
#include <string>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/message_key.h"
#include "viewer/state_viewer.h"

namespace mrsim {

struct ViewOptions {
  std::string scenario;
  std::string lcm_url;  // empty: LCM's default
  AuthFlags auth;
  std::string prefix = kDefaultChannelPrefix;
  std::string from_log;    // .lcmlog to replay instead of listening
  std::string out;         // MP4 path
  std::string frames_dir;  // PNG folder
  double fps = 30.0;
  bool window = false;
  // When the simulator says it stops (or goes silent): render the frames
  // still due, finish the output and exit 0 (a launch's finish policy).
  bool exit_with_sim = false;
  int64_t max_frames = 0;  // 0: until stopped or the log ends
  // States kept per robot for frames not rendered yet (at most one per
  // frame); 0: kRecordingQueue when writing frames, kWindowQueue for a
  // window alone, which should show the newest.
  int queue = 0;
  static constexpr int kRecordingQueue = 3600;  // 2 min behind at 30 fps
  static constexpr int kWindowQueue = 8;
  int QueueOrDefault() const {
    if (queue > 0) return queue;
    return out.empty() && frames_dir.empty() ? kWindowQueue : kRecordingQueue;
  }
  ViewerOptions viewer;  // quality.shadow_size defaults to 1024 here

  ViewOptions() { viewer.quality.shadow_size = kDefaultShadowSize; }
  // MuJoCo's 4096 shadow map makes software rendering several times slower
  // for little visible gain at video sizes.
  static constexpr int kDefaultShadowSize = 1024;
};

// Parses argv. Returns -1 to go on, or an exit code: 0 after --help or
// --version, 2 on flags CLI11 refuses (its message printed, as by every
// mrsim program); throws UsageError for values it refuses itself.
int ParseViewOptions(int argc, char** argv, ViewOptions* options);

}  // namespace mrsim
