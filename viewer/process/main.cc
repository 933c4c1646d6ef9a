// mrsim-view: subscribes to the robot states of a scenario (or replays an
// .lcmlog), poses the model rebuilt from the same scenario and renders
// frames at fixed simulation-time steps to MP4 / PNG, off-screen; with
// --window, live too. It only listens, so it never slows the simulator.
// The work is in view_command.h and viewer/frame_pump.h.
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <stdexcept>

#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario/scenario_xml.h"
#include "viewer/process/view_command.h"
#include "viewer/process/view_options.h"

int main(int argc, char** argv) {
  mrsim::ViewOptions options;
  try {
    const int parsed = mrsim::ParseViewOptions(argc, argv, &options);
    if (parsed >= 0) return parsed;
    mrsim::InstallStopHandlers();
    mrsim::CheckViewOptions(options);
    std::unique_ptr<mrsim::SignedLcm> lcm;
    if (options.from_log.empty()) {
      lcm = std::make_unique<mrsim::SignedLcm>(
          options.lcm_url, options.auth.Load(), [](const std::string& line) {
            std::fprintf(stderr, "mrsim-view: %s\n", line.c_str());
          });
    }
    return mrsim::RunView(options, lcm.get(), stderr);
  } catch (const mrsim::UsageError& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 2;
  } catch (const mrsim::ViewInputError& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 2;
  } catch (const mrsim::ScenarioError& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 1;
  }
}
