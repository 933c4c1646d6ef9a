// Every message decoder: the first byte picks the type, the rest is the
// datagram. A datagram either fails the wire check or decodes, and then
// it re-encodes to exactly the same bytes, less a signature trailer
// (nothing was read that was not there) and the logger's independent walk of
// the layout accepts it too.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <vector>

#include "lcmtypes/runtime/decode.h"
#include "logger/generic_flattener.h"
#include "logger/lcm_type_registry.h"
#include "mrsim/message_types.hpp"

namespace {

using mrsim::LcmTypeRegistry;

const LcmTypeRegistry& Registry() {
  static const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  return registry;
}

template <class Message>
void Check(const uint8_t* data, size_t size) {
  Message msg;
  if (!mrsim::DecodeMessage(data, size, &msg)) return;
  // A reader without the key takes a signed message and ignores its
  // signature trailer (decode.h): the message is what comes before it.
  if (static_cast<size_t>(msg.getEncodedSize()) != size) {
    size = mrsim::MessageAuth::SizeWithoutTrailer(data, size);
  }
  std::vector<uint8_t> again(static_cast<size_t>(msg.getEncodedSize()));
  if (again.size() != size ||
      msg.encode(again.data(), 0, static_cast<int>(again.size())) !=
          static_cast<int>(size) ||
      std::memcmp(again.data(), data, size) != 0) {
    std::abort();  // accepted bytes must be exactly one message
  }
  const mrsim::LcmStruct* type = Registry().FindByHash(Message::getHash());
  if (type == nullptr ||
      !mrsim::GenericFlattener(Registry(), *type).IsWellFormed(data, size)) {
    std::abort();  // the two walks of the layout disagree
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  // Every type, in name order (mrsim/message_types.hpp, generated from the
  // .lcm files; the log_flatten target and the seed writer use the same
  // order), so a new message type is fuzzed without touching this file.
  using CheckFn = void (*)(const uint8_t*, size_t);
#define MRSIM_CHECK_ENTRY(T, I) &Check<mrsim::T>,
  static constexpr CheckFn kChecks[] = {MRSIM_MESSAGE_TYPES(MRSIM_CHECK_ENTRY)};
#undef MRSIM_CHECK_ENTRY
  static_assert(std::size(kChecks) == MRSIM_MESSAGE_TYPE_COUNT);
  kChecks[data[0] % std::size(kChecks)](data + 1, size - 1);
  return 0;
}
