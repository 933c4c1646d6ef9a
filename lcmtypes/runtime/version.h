// The --version line of every program, from common/version.h (the one
// definition of the project version).
#pragma once

#include <string>

namespace mrsim {

// "0.1.0"
const char* ProjectVersion();
// "<program> <version>", what --version prints.
std::string VersionLine(const std::string& program);

}  // namespace mrsim
