// The logger's flatteners (mrsim-log and the studio's plots turn every
// message into a CSV row with them): a stream of datagrams, each a 2-byte
// length and the bytes, on one channel whose type the first byte picks.
// Shapes change from message to message. Never a crash, and a row has as
// many cells as the columns named for it.
#include <cstdint>
#include <cstdlib>
#include <memory>

#include "logger/generic_flattener.h"
#include "logger/lcm_type_registry.h"
#include "logger/robot_state_flattener.h"

namespace {

size_t Cells(const std::string& row) {
  size_t n = 1;
  bool quoted = false;
  for (char c : row) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) ++n;
  }
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  static const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  static const std::vector<const LcmStruct*> types = registry.structs();
  if (size == 0 || types.empty()) return 0;
  const LcmStruct& type = *types[data[0] % types.size()];
  std::unique_ptr<MessageFlattener> flattener;
  if (type.full_name() == "mrsim.robot_state_t") {
    flattener = std::make_unique<RobotStateFlattener>(registry);
  } else {
    flattener = std::make_unique<GenericFlattener>(registry, type);
  }
  FlatRow row;
  size_t at = 1;
  while (at + 2 <= size) {
    const size_t n =
        std::min<size_t>((data[at] << 8) | data[at + 1], size - at - 2);
    at += 2;
    if (flattener->Flatten(data + at, n, &row) &&
        Cells(row.values) != flattener->columns().size()) {
      std::abort();  // a row that does not fit its header
    }
    at += n;
  }
  return 0;
}
