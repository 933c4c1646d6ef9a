// mrsim-camera's command line: the flags (CLI11) and the node options they
// make, so main only parses, wires and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "camera/camera_node.h"
#include "lcmtypes/runtime/message_key.h"

namespace mrsim {

struct CameraCommandLine {
  std::string scenario_path;
  std::string lcm_url;
  AuthFlags auth;
  std::string clock = "realtime";
  std::string encoding = kCameraEncodingRgb8;
  int jpeg_quality = 90;
  CameraNodeOptions options;  // complete after Finish()

  void AddFlags(CLI::App& app);
  // Checks what CLI11 cannot (the clock and encoding words, the quality)
  // and fills options; throws UsageError naming the flag.
  void Finish();
  // "listening on ...": what a launch file waits for.
  std::string StartLine(const CameraNode& node) const;
};

}  // namespace mrsim
