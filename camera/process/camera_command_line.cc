#include "camera/process/camera_command_line.h"

#include <sstream>
#include <stdexcept>

#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"

namespace mrsim {

void CameraCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-camera"));
  app.add_option("--scenario", scenario_path,
                 "Scenario file mrsim-sim runs (its cameras are pictured)")
      ->required();
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  AddAuthFlags(app, auth);
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--clock", clock,
                 "The simulator's clock: realtime or fast (never slows it; "
                 "frames it cannot keep up with are dropped and counted) or "
                 "lockstep (pictures every due state, then answers it: list "
                 "--sender in mrsim-sim --controllers)")
      ->capture_default_str();
  app.add_option("--encoding", encoding, "Picture encoding: rgb8 or jpeg")
      ->capture_default_str();
  app.add_option("--jpeg-quality", jpeg_quality,
                 "JPEG quality, 1..100 (with --encoding jpeg)")
      ->capture_default_str();
  app.add_option("--sender", options.sender,
                 "Sender name of the pictures and of the lockstep answers")
      ->capture_default_str();
  app.add_option("--robot", options.robot,
                 "Only this robot's cameras (default: every robot's)");
  app.add_flag("--exit-with-sim", options.exit_with_sim,
               "Exit when the simulator stops (or is silent for 5 s)");
}

void CameraCommandLine::Finish() {
  try {
    options.clock = ParseClockMode(clock, "--clock");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (encoding == kCameraEncodingRgb8) {
    options.jpeg_quality = 0;
  } else if (encoding == kCameraEncodingJpeg) {
    if (jpeg_quality < 1 || jpeg_quality > 100) {
      throw UsageError("--jpeg-quality " + std::to_string(jpeg_quality) +
                       ": expected 1..100");
    }
    options.jpeg_quality = jpeg_quality;
  } else {
    throw UsageError("--encoding '" + encoding + "': expected rgb8 or jpeg");
  }
  if (options.sender.empty() || options.sender.size() > 256) {
    throw UsageError("--sender: expected 1..256 characters");
  }
}

std::string CameraCommandLine::StartLine(const CameraNode& node) const {
  std::ostringstream line;
  line << "mrsim-camera: " << node.imaged().size() << " camera(s), "
       << (options.jpeg_quality > 0 ? "jpeg" : "rgb8") << ", clock "
       << ToString(options.clock);
  if (options.clock == ClockMode::kLockstep) {
    line << " (answers as '" << options.sender << "')";
  }
  line << ", listening on " << node.StateChannels().size()
       << " state channel(s)";
  return line.str();
}

}  // namespace mrsim
