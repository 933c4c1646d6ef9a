// The number reader of checkpoints and state files: any text either reads
// as a number that prints back to the same value, or is refused.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "common/exact_number.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto value = mrsim::ParseWholeNumber(text);
  if (value && !std::isnan(*value)) {
    const auto again = mrsim::ParseWholeNumber(mrsim::ExactNumber(*value));
    if (!again || *again != *value) std::abort();  // must round-trip exactly
  }
  return 0;
}
