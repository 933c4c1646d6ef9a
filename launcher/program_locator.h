// Finds an mrsim program the way a user expects: next to the running
// launcher first (build/bin or the install's bin), then on PATH.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

// Directories searched for programs: the directory of argv0, the bin
// directory beside the resolved executable, then PATH.
std::vector<std::string> ProgramSearchPath(const std::string& argv0);

// A path, or the first executable named `program` on the search path.
// Throws std::runtime_error: for an mrsim-* name, the mrsim programs there
// are (and the nearest, "did you mean"), for others the directories tried.
std::string FindProgram(const std::string& program,
                        const std::vector<std::string>& search_path);

// The mrsim-TOOL programs on the search path, as TOOL names, sorted.
std::vector<std::string> ListTools(const std::vector<std::string>& search_path);

}  // namespace mrsim
