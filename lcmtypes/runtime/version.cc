#include "lcmtypes/runtime/version.h"

#include "common/version.h"

namespace mrsim {

const char* ProjectVersion() { return kVersion; }

std::string VersionLine(const std::string& program) {
  return program + " " + ProjectVersion();
}

}  // namespace mrsim
