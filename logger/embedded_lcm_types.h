// The text of every lcmtypes/mrsim/*.lcm file, compiled in at build time so
// the logger decodes our messages without the source tree.
#pragma once

#include <vector>

namespace mrsim {

struct EmbeddedLcmSource {
  const char* name;  // file name, e.g. "robot_state_t.lcm"
  const char* text;
};

const std::vector<EmbeddedLcmSource>& EmbeddedLcmSources();

}  // namespace mrsim
