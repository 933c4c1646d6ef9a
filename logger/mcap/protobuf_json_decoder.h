// Decodes the protobuf messages of an MCAP channel into the JSON text the
// JSON encoding of mrsim-log --mcap writes for the same message (members in
// field order, numbers as JsonWriter writes them, NaN as null, bytes and
// row wrappers (lcm_protobuf_schema.h) as arrays), so a reader handles both
// encodings with one path: McapReader's users, Python's mrsim.read_mcap.
// The schema and the payloads come from a file, so both are hostile: the
// schema is built by libprotobuf's DescriptorPool (which checks it), the
// payload parsed by libprotobuf (nesting at most 100 deep), and the text
// made from one payload is bounded (kMaxJsonPerByte per byte, plus 1 MiB).
// This is the reader's path; the logger writes with LcmProtobufEncoder.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "lcmtypes/json/json_writer.h"
#include "logger/mcap/mcap_reader.h"

namespace google::protobuf {
class DescriptorPool;
class DynamicMessageFactory;
class Message;
}  // namespace google::protobuf

namespace mrsim::mcap {

class ProtobufJsonDecoder {
 public:
  static constexpr size_t kMaxJsonPerByte = 64;

  // Builds message `message_name` from `descriptor_set` (a serialised
  // FileDescriptorSet, files after those they import). `where` names the
  // schema in errors. Throws McapError saying what is wrong.
  ProtobufJsonDecoder(std::string_view descriptor_set,
                      const std::string& message_name,
                      const std::string& where);
  ~ProtobufJsonDecoder();
  ProtobufJsonDecoder(const ProtobufJsonDecoder&) = delete;
  ProtobufJsonDecoder& operator=(const ProtobufJsonDecoder&) = delete;

  // The JSON text of one payload, valid until the next call. Throws
  // McapError when the payload is not a message of the type, or its text
  // would be over the bound.
  std::string_view ToJson(std::string_view payload);

 private:
  void Message(const google::protobuf::Message& m, int depth);

  std::string where_;
  std::unique_ptr<google::protobuf::DescriptorPool> pool_;
  std::unique_ptr<google::protobuf::DynamicMessageFactory> factory_;
  std::unique_ptr<google::protobuf::Message> message_;
  JsonWriter json_;
  size_t limit_ = 0;
};

// A channel's messages as JSON text, whatever their encoding: "json" as
// they are, "protobuf" through a ProtobufJsonDecoder made once per schema.
class McapJsonPayloads {
 public:
  McapJsonPayloads();
  ~McapJsonPayloads();
  // The JSON text of `m` (valid until the next call). Throws McapError for
  // an encoding it does not read, a schema that does not build, or a
  // payload that does not decode.
  std::string_view Text(const McapMessage& m);

 private:
  struct Decoders;
  std::unique_ptr<Decoders> decoders_;
};

}  // namespace mrsim::mcap
