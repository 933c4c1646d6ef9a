// The protobuf side of MCAP files (docs/logger.md, "--mcap-encoding"): the
// logger's encoder fed any LCM bytes, and the readers' decoder fed any
// schema and payload. The first byte says which:
//   0: an LCM message (fingerprint first) of any built-in type, encoded by
//      LcmProtobufEncoder; one it accepts must decode again with the schema
//      made for its type (never refused, never a crash);
//   1: a protobuf payload of built-in type number input[1] (name order),
//      decoded with that type's schema;
//   2: a schema (u16 little-endian length, then a FileDescriptorSet) and a
//      payload, decoded as the schema's first message.
// Refusals (McapError) are the expected outcome for most inputs.
#include <google/protobuf/descriptor.pb.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "logger/lcm_type_registry.h"
#include "logger/mcap/lcm_protobuf_encoder.h"
#include "logger/mcap/lcm_protobuf_schema.h"
#include "logger/mcap/mcap_reader.h"
#include "logger/mcap/protobuf_json_decoder.h"

namespace {

const mrsim::LcmTypeRegistry& Registry() {
  static const mrsim::LcmTypeRegistry registry =
      mrsim::LcmTypeRegistry::WithBuiltinTypes();
  return registry;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  if (size < 2) return 0;
  const LcmTypeRegistry& registry = Registry();
  const std::string_view rest(reinterpret_cast<const char*>(data + 1),
                              size - 1);
  try {
    if (data[0] == 0) {
      if (rest.size() < 8) return 0;
      int64_t hash = 0;
      for (size_t k = 0; k < 8; ++k) {
        hash = static_cast<int64_t>((static_cast<uint64_t>(hash) << 8) |
                                    static_cast<uint8_t>(rest[k]));
      }
      const LcmStruct* type = registry.FindByHash(hash);
      if (type == nullptr) return 0;
      LcmProtobufEncoder encoder(registry, *type);
      if (!encoder.Encode(data + 1, size - 1)) return 0;
      mcap::ProtobufJsonDecoder decoder(
          LcmProtobufDescriptorSet(registry, *type), type->full_name(), "fuzz");
      try {
        decoder.ToJson(encoder.view());
      } catch (const mcap::McapError&) {
        std::abort();  // what the encoder writes always decodes
      }
    } else if (data[0] == 1) {
      const auto structs = registry.structs();
      const LcmStruct& type = *structs[data[1] % structs.size()];
      mcap::ProtobufJsonDecoder decoder(
          LcmProtobufDescriptorSet(registry, type), type.full_name(), "fuzz");
      decoder.ToJson(rest.substr(1));
    } else if (data[0] == 2) {
      if (rest.size() < 2) return 0;
      const size_t n =
          static_cast<uint8_t>(rest[0]) |
          (static_cast<size_t>(static_cast<uint8_t>(rest[1])) << 8);
      if (n > rest.size() - 2) return 0;
      const std::string_view schema = rest.substr(2, n);
      google::protobuf::FileDescriptorSet set;
      if (!set.ParseFromArray(schema.data(), static_cast<int>(schema.size())) ||
          set.file_size() == 0 || set.file(0).message_type_size() == 0) {
        return 0;
      }
      const std::string& package = set.file(0).package();
      const std::string name = (package.empty() ? "" : package + ".") +
                               set.file(0).message_type(0).name();
      mcap::ProtobufJsonDecoder decoder(schema, name, "fuzz");
      decoder.ToJson(rest.substr(2 + n));
    }
  } catch (const mcap::McapError&) {
    // Refused, saying why.
  }
  return 0;
}
