// The MCAP reader (Python's read_mcap, and any tool reading a file
// mrsim-log wrote or someone sent): any bytes, a file or the start of one.
// Never a crash, never memory beyond a chunk's checked size. Each message's
// bytes also go through JsonWriter::String (how a message's strings from
// the wire become JSON): the text it writes holds no raw control byte.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "lcmtypes/json/json_writer.h"
#include "logger/mcap/mcap_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  JsonWriter json;
  try {
    mcap::ReadMcap(bytes, "fuzz.mcap", [&](const mcap::McapMessage& m) {
      if (m.channel == nullptr) std::abort();
      json.Clear();
      json.String(m.data);
      for (char c : json.view()) {
        if (static_cast<unsigned char>(c) < 0x20) std::abort();
      }
    });
  } catch (const mcap::McapError&) {
    // Refused, naming the offset: the expected outcome for most inputs.
  }
  return 0;
}
