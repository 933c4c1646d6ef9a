// Where a program finds mrsim's data (scenarios, launch files, docs) when
// it is installed rather than run from the source tree.
#pragma once

#include <string>

namespace mrsim {

// The data folder of the program at `executable`: MRSIM_DATA_DIR when set,
// else <folder of executable>/../share/mrsim when that exists, else "".
// Relative to the program, so /usr/bin finds /usr/share/mrsim and a
// --prefix or staging install finds its own copy; in the build tree there
// is none and programs keep their paths relative to the source tree.
std::string DataDirFor(const std::string& executable);

// DataDirFor() of the running program (/proc/self/exe).
std::string DataDir();

// DataDir()/relative when that exists, else "".
std::string FindDataFile(const std::string& relative);

}  // namespace mrsim
