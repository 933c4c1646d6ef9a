#include "studio/app/studio_flags.h"

#include "lcmtypes/runtime/version.h"

namespace mrsim::studio {

void AddStudioFlags(CLI::App* cli, StudioFlags* f) {
  AppOptions& o = f->options;
  cli->add_option("SCENARIO", f->scenario, "Scenario file to open (or create)");
  cli->add_option("--screenshot", f->screenshot,
                  "Render the window once off-screen to this PNG and exit");
  cli->add_option("--width", o.width, "Window width")->capture_default_str();
  cli->add_option("--height", o.height, "Window height")->capture_default_str();
  cli->add_option("--ui-scale", o.ui_scale,
                  "Text and panel size (1: 15 px text; default: the "
                  "monitor's content scale)")
      ->check(CLI::Range(0.0f, 4.0f));
  cli->add_option("--layout-dump", o.layout_dump,
                  "Write widget rectangles and state here (for tests)");
  cli->add_option("--key-file", f->key_file,
                  "Sign the live session's messages, and those of the "
                  "processes it starts, with this key (default: "
                  "$MRSIM_KEY_FILE; docs/security.md)");
  cli->set_version_flag("--version", mrsim::VersionLine("mrsim-studio"));
}

}  // namespace mrsim::studio
