// The gait file reader on any bytes: a gait whose parameters the gait
// controller accepts, or a GaitFileError. fuzz-dict: xml
#include <cstdint>
#include <cstdlib>
#include <string>

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_parameters.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    const mrsim::Gait gait = mrsim::ReadGaitString(xml, "fuzz.gait.xml");
    // What it read is what the controller runs: it must validate, and
    // write and read back to the same parameters.
    mrsim::ValidateGaitParameters(gait.parameters);
    const mrsim::Gait again =
        mrsim::ReadGaitString(mrsim::WriteGaitString(gait), "fuzz.gait.xml");
    if (!(again.parameters == gait.parameters)) std::abort();
  } catch (const mrsim::GaitFileError&) {
  }
  return 0;
}
