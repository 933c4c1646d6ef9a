#include "viewer/process/view_options.h"

#include <CLI/CLI.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli_exit.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"

namespace mrsim {
namespace {

bool ParseVector(const std::string& text, Eigen::Vector3d* v) {
  std::stringstream in(text);
  std::string part;
  std::vector<double> values;
  while (std::getline(in, part, ',')) {
    try {
      size_t used = 0;
      values.push_back(std::stod(part, &used));
      if (used != part.size()) return false;
    } catch (...) {
      return false;
    }
  }
  if (values.size() != 3) return false;
  *v = Eigen::Vector3d(values[0], values[1], values[2]);
  return v->allFinite();
}

}  // namespace

int ParseViewOptions(int argc, char** argv, ViewOptions* o) {
  CLI::App app{
      "mrsim-view: renders the robots of a scenario from their state stream "
      "(live LCM or an .lcmlog) to MP4 or PNG frames, off-screen; with "
      "--window and a display, live as well."};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-view"));
  app.add_option("scenario", o->scenario, "Scenario XML file")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--lcm-url", o->lcm_url, "LCM URL (default: LCM's own)");
  AddAuthFlags(app, o->auth);
  app.add_option("--prefix", o->prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--robot", o->viewer.follow_robot,
                 "Robot the camera follows and the overlay describes "
                 "(default: the first)");
  app.add_option("--from-log", o->from_log,
                 "Replay robot states from an .lcmlog (as fast as it "
                 "renders) instead of listening")
      ->check(CLI::ExistingFile);
  auto* out = app.add_option("--out", o->out, "Write an MP4 video here");
  auto* dir = app.add_option("--frames-dir", o->frames_dir,
                             "Write PNG frames frame_<k>.png here");
  out->excludes(dir);
  app.add_option("--width", o->viewer.width, "Frame width (pixels)")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192));
  app.add_option("--height", o->viewer.height, "Frame height (pixels)")
      ->capture_default_str()
      ->check(CLI::Range(16, 8192));
  app.add_option("--fps", o->fps, "Frames per second of simulation time")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  std::string camera = "follow";
  app.add_option("--camera", camera,
                 "follow (track the robot's centre of mass) or fixed")
      ->capture_default_str()
      ->check(CLI::IsMember({"follow", "fixed"}));
  app.add_option("--azimuth", o->viewer.camera.azimuth,
                 "Camera azimuth (deg, about +z from +x)")
      ->capture_default_str();
  app.add_option("--elevation", o->viewer.camera.elevation,
                 "Camera elevation (deg, negative looks down)")
      ->capture_default_str()
      ->check(CLI::Range(-89.0, 89.0));
  app.add_option("--distance", o->viewer.camera.distance,
                 "Camera distance from the look-at point (m)")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 100.0));
  std::string lookat;
  app.add_option("--lookat", lookat,
                 "x,y,z: look-at point (fixed) or offset from the centre of "
                 "mass (follow), m");
  app.add_flag("--window", o->window,
               "Also show a live window when a display exists");
  app.add_flag("--exit-with-sim", o->exit_with_sim,
               "Exit when the simulator stops (or is silent for 5 s), after "
               "rendering every frame it is still behind on")
      ->excludes("--from-log");
  app.add_option("--overlay", o->viewer.gait,
                 "Gait name shown in the overlay (default: what mrsim-gait "
                 "reports running, else the latest gait command)");
  bool no_overlay = false;
  bool no_rays = false;
  app.add_flag("--no-overlay", no_overlay, "No text overlay");
  app.add_flag("--no-rays", no_rays, "Do not draw distance-sensor rays");
  app.add_option("--samples", o->viewer.quality.samples,
                 "Anti-aliasing samples (0: off, -1: the model's, 4)")
      ->capture_default_str()
      ->check(CLI::Range(-1, 16));
  app.add_option("--shadow-size", o->viewer.quality.shadow_size,
                 "Shadow map size in pixels (0: no shadows, -1: the model's, "
                 "MuJoCo's default 4096). Larger is much slower without a GPU")
      ->capture_default_str()
      ->check(CLI::Range(-1, 16384));
  app.add_option("--max-frames", o->max_frames,
                 "Stop after this many frames (0: no limit)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--queue", o->queue,
                 "Frames a slow viewer may fall behind the simulation: states "
                 "kept per robot for frames not rendered yet, one per frame; "
                 "beyond, the oldest are dropped and their frames show a "
                 "later state (default: 3600 when writing frames, 8 for a "
                 "window alone, which shows the newest)")
      ->check(CLI::Range(2, 1000000));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  if (!lookat.empty() && !ParseVector(lookat, &o->viewer.camera.lookat)) {
    throw UsageError("--lookat: expected three numbers x,y,z, got '" + lookat +
                     "'");
  }
  o->viewer.camera.mode =
      camera == "fixed" ? CameraMode::kFixed : CameraMode::kFollow;
  o->viewer.overlay = !no_overlay;
  o->viewer.rays = !no_rays;
  if (o->out.empty() && o->frames_dir.empty() && !o->window) {
    throw UsageError(
        "nothing to show: give --out FILE.mp4, --frames-dir DIR or --window");
  }
  return -1;
}

}  // namespace mrsim
