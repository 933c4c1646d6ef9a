// The network file reader on any bytes: a network that evaluates to
// targets within its range and writes and reads back to the same weights,
// or a NetworkFileError. fuzz-dict: xml
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nn_controller/network_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    mrsim::NetworkFile file = mrsim::ReadNetworkString(xml, "fuzz.net.xml");
    const mrsim::NetworkFile again = mrsim::ReadNetworkString(
        mrsim::WriteNetworkString(file.network, file.name), "fuzz.net.xml");
    if (again.network.weights() != file.network.weights() ||
        again.network.period() != file.network.period() ||
        !(again.network.shape() == file.network.shape())) {
      std::abort();
    }
    mrsim::NnObservation o;
    o.time = 1.25;
    o.angles.assign(static_cast<size_t>(file.network.shape().joints), 0.5);
    o.speeds = o.angles;
    for (double t : file.network.Evaluate(o)) {
      if (!(std::abs(t) <= file.network.shape().output_range)) std::abort();
    }
  } catch (const mrsim::NetworkFileError&) {
  }
  return 0;
}
