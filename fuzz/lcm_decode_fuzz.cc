// Every message decoder: the first byte picks the type, the rest is the
// datagram. A datagram either fails the wire check or decodes, and then
// it re-encodes to exactly the same bytes, less a signature trailer
// (nothing was read that was not there) and the logger's independent walk of
// the layout accepts it too.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "lcmtypes/runtime/decode.h"
#include "logger/generic_flattener.h"
#include "logger/lcm_type_registry.h"

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
  const uint8_t type = data[0];
  ++data;
  --size;
  // Every type, in name order (the log_flatten target and the seed
  // writer use the same order).
  switch (type % 18) {
    case 0:
      Check<mrsim::gait_command_t>(data, size);
      break;
    case 1:
      Check<mrsim::gait_status_t>(data, size);
      break;
    case 2:
      Check<mrsim::joint_command_t>(data, size);
      break;
    case 3:
      Check<mrsim::joint_state_t>(data, size);
      break;
    case 4:
      Check<mrsim::opt_chunk_request_t>(data, size);
      break;
    case 5:
      Check<mrsim::opt_chunk_t>(data, size);
      break;
    case 6:
      Check<mrsim::opt_heartbeat_t>(data, size);
      break;
    case 7:
      Check<mrsim::opt_job_t>(data, size);
      break;
    case 8:
      Check<mrsim::opt_progress_t>(data, size);
      break;
    case 9:
      Check<mrsim::opt_result_t>(data, size);
      break;
    case 10:
      Check<mrsim::opt_run_t>(data, size);
      break;
    case 11:
      Check<mrsim::pose_t>(data, size);
      break;
    case 12:
      Check<mrsim::robot_state_t>(data, size);
      break;
    case 13:
      Check<mrsim::scene_state_t>(data, size);
      break;
    case 14:
      Check<mrsim::sensor_module_state_t>(data, size);
      break;
    case 15:
      Check<mrsim::sensor_reading_t>(data, size);
      break;
    case 16:
      Check<mrsim::sim_control_t>(data, size);
      break;
    default:
      Check<mrsim::sim_status_t>(data, size);
      break;
  }
  return 0;
}
