#include "lcmtypes/runtime/version.h"

namespace mrsim {

// MRSIM_PROJECT_VERSION comes from lcmtypes/CMakeLists.txt (PROJECT_VERSION).
const char* ProjectVersion() { return MRSIM_PROJECT_VERSION; }

std::string VersionLine(const std::string& program) {
  return program + " " + ProjectVersion();
}

}  // namespace mrsim
