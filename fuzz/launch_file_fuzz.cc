// The launch file reader on any bytes (it reads a path, so each input is
// written to a private file first): a launch or a LaunchError.
// fuzz-dict: xml
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "launcher/launch_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string kPath =
      "/tmp/mrsim-fuzz-" + std::to_string(::getpid()) + ".launch";
  {
    std::ofstream out(kPath, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data),
              static_cast<std::streamsize>(size));
  }
  try {
    mrsim::ReadLaunchFile(kPath, {});
  } catch (const mrsim::LaunchError&) {
  }
  return 0;
}
