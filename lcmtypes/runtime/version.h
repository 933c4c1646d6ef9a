// The project's version (CMake's PROJECT_VERSION), one definition for every
// program's --version.
#pragma once

#include <string>

namespace mrsim {

// "0.1.0"
const char* ProjectVersion();
// "<program> <version>", what --version prints.
std::string VersionLine(const std::string& program);

}  // namespace mrsim
