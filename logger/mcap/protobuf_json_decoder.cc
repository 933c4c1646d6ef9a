#include "logger/mcap/protobuf_json_decoder.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/descriptor.pb.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/message.h>

#include <map>
#include <string>

#include "logger/mcap/lcm_protobuf_schema.h"

namespace mrsim::mcap {
namespace {

namespace pb = google::protobuf;

// The first error the pool reports about a file of the schema.
class FirstError : public pb::DescriptorPool::ErrorCollector {
 public:
  void AddError(const std::string& filename, const std::string& element_name,
                const pb::Message*, ErrorLocation,
                const std::string& message) override {
    if (text.empty()) text = filename + ": " + element_name + ": " + message;
  }
  std::string text;
};

// A row wrapper of lcm_protobuf_schema.h: NAME_rowK nested in its struct's
// message, with one field, values = 1.
bool IsRowWrapper(const pb::Descriptor& d) {
  const std::string& name = d.name();
  const size_t at = name.rfind(kProtobufRowSuffix);
  return d.containing_type() != nullptr && at != std::string::npos &&
         at + 4 < name.size() && d.field_count() == 1 &&
         d.field(0)->number() == 1 && d.field(0)->name() == "values";
}

}  // namespace

ProtobufJsonDecoder::ProtobufJsonDecoder(std::string_view descriptor_set,
                                         const std::string& message_name,
                                         const std::string& where)
    : where_(where), pool_(std::make_unique<pb::DescriptorPool>()) {
  pb::FileDescriptorSet set;
  if (descriptor_set.size() > static_cast<size_t>(INT32_MAX) ||
      !set.ParseFromArray(descriptor_set.data(),
                          static_cast<int>(descriptor_set.size()))) {
    throw McapError(where_ +
                    ": the protobuf schema is not a "
                    "FileDescriptorSet");
  }
  for (const pb::FileDescriptorProto& file : set.file()) {
    FirstError error;
    if (pool_->BuildFileCollectingErrors(file, &error) == nullptr) {
      throw McapError(where_ + ": the protobuf schema's file " + file.name() +
                      " does not build: " + error.text);
    }
  }
  const pb::Descriptor* type = pool_->FindMessageTypeByName(message_name);
  if (type == nullptr) {
    throw McapError(where_ + ": the protobuf schema has no message " +
                    message_name);
  }
  factory_ = std::make_unique<pb::DynamicMessageFactory>(pool_.get());
  message_.reset(factory_->GetPrototype(type)->New());
}

ProtobufJsonDecoder::~ProtobufJsonDecoder() {
  message_.reset();  // before the factory that made it
}

std::string_view ProtobufJsonDecoder::ToJson(std::string_view payload) {
  json_.Clear();
  message_->Clear();
  if (payload.size() > static_cast<size_t>(INT32_MAX) ||
      !message_->ParseFromArray(payload.data(),
                                static_cast<int>(payload.size()))) {
    throw McapError(where_ + ": a message of " +
                    std::to_string(payload.size()) + " bytes is not a " +
                    message_->GetDescriptor()->full_name());
  }
  limit_ = kMaxJsonPerByte * payload.size() + (1 << 20);
  Message(*message_, 0);
  return json_.view();
}

void ProtobufJsonDecoder::Message(const pb::Message& m, int depth) {
  const pb::Descriptor& d = *m.GetDescriptor();
  const pb::Reflection& r = *m.GetReflection();
  // Parsing nests at most 100 deep; unset messages are written as null,
  // so a schema that contains itself does not nest further.
  if (depth > 200) throw McapError(where_ + ": messages nested too deep");
  const bool row = IsRowWrapper(d);
  if (!row) json_.Raw("{");
  for (int i = 0; i < d.field_count(); ++i) {
    if (json_.size() > limit_) {
      throw McapError(where_ + ": a message's text would be over " +
                      std::to_string(limit_) + " bytes");
    }
    const pb::FieldDescriptor& f = *d.field(i);
    if (!row) {
      if (i > 0) json_.Raw(",");
      json_.String(f.name());
      json_.Raw(":");
    }
    const bool repeated = f.is_repeated();
    const int n = repeated ? r.FieldSize(m, &f) : 1;
    if (repeated) json_.Raw("[");
    for (int k = 0; k < n; ++k) {
      if (k > 0) json_.Raw(",");
      if ((k & 1023) == 1023 && json_.size() > limit_) {
        throw McapError(where_ + ": a message's text would be over " +
                        std::to_string(limit_) + " bytes");
      }
      switch (f.cpp_type()) {
        case pb::FieldDescriptor::CPPTYPE_INT32:
          json_.Int(repeated ? r.GetRepeatedInt32(m, &f, k)
                             : r.GetInt32(m, &f));
          break;
        case pb::FieldDescriptor::CPPTYPE_INT64:
          json_.Int(repeated ? r.GetRepeatedInt64(m, &f, k)
                             : r.GetInt64(m, &f));
          break;
        case pb::FieldDescriptor::CPPTYPE_UINT32:
          json_.Int(repeated ? r.GetRepeatedUInt32(m, &f, k)
                             : r.GetUInt32(m, &f));
          break;
        case pb::FieldDescriptor::CPPTYPE_UINT64:
          json_.Raw(std::to_string(repeated ? r.GetRepeatedUInt64(m, &f, k)
                                            : r.GetUInt64(m, &f)));
          break;
        case pb::FieldDescriptor::CPPTYPE_DOUBLE:
          json_.Double(repeated ? r.GetRepeatedDouble(m, &f, k)
                                : r.GetDouble(m, &f));
          break;
        case pb::FieldDescriptor::CPPTYPE_FLOAT:
          json_.Double(static_cast<double>(
              repeated ? r.GetRepeatedFloat(m, &f, k) : r.GetFloat(m, &f)));
          break;
        case pb::FieldDescriptor::CPPTYPE_BOOL:
          json_.Bool(repeated ? r.GetRepeatedBool(m, &f, k) : r.GetBool(m, &f));
          break;
        case pb::FieldDescriptor::CPPTYPE_ENUM:
          json_.Int(repeated ? r.GetRepeatedEnumValue(m, &f, k)
                             : r.GetEnumValue(m, &f));
          break;
        case pb::FieldDescriptor::CPPTYPE_STRING: {
          std::string scratch;
          const std::string& s =
              repeated ? r.GetRepeatedStringReference(m, &f, k, &scratch)
                       : r.GetStringReference(m, &f, &scratch);
          if (f.type() != pb::FieldDescriptor::TYPE_BYTES) {
            json_.String(s);
            break;
          }
          // Bytes as the JSON encoding writes an LCM byte array: numbers.
          json_.Raw("[");
          for (size_t b = 0; b < s.size(); ++b) {
            if (b > 0) json_.Raw(",");
            json_.Int(static_cast<uint8_t>(s[b]));
          }
          json_.Raw("]");
          break;
        }
        case pb::FieldDescriptor::CPPTYPE_MESSAGE:
          if (!repeated && !r.HasField(m, &f)) {
            json_.Raw("null");
          } else {
            Message(
                repeated ? r.GetRepeatedMessage(m, &f, k) : r.GetMessage(m, &f),
                depth + 1);
          }
          break;
      }
    }
    if (repeated) json_.Raw("]");
  }
  if (!row) json_.Raw("}");
}

struct McapJsonPayloads::Decoders {
  struct Entry {
    std::string name, data;  // what it was made from
    std::unique_ptr<ProtobufJsonDecoder> decoder;
  };
  std::map<uint16_t, Entry> by_schema;
};

McapJsonPayloads::McapJsonPayloads()
    : decoders_(std::make_unique<Decoders>()) {}
McapJsonPayloads::~McapJsonPayloads() = default;

std::string_view McapJsonPayloads::Text(const McapMessage& m) {
  const std::string& encoding = m.channel->message_encoding;
  if (encoding == "json") return m.data;
  if (encoding != "protobuf") {
    throw McapError("channel " + m.channel->topic + ": message encoding '" +
                    encoding + "' is not read (json and protobuf are)");
  }
  if (m.schema == nullptr || m.schema->encoding != "protobuf") {
    throw McapError("channel " + m.channel->topic +
                    ": protobuf messages without a protobuf schema");
  }
  // A schema id a file defines again with other contents gets a new one.
  Decoders::Entry& e = decoders_->by_schema[m.schema->id];
  if (e.decoder == nullptr || e.name != m.schema->name ||
      e.data != m.schema->data) {
    e.decoder.reset();
    e.decoder = std::make_unique<ProtobufJsonDecoder>(
        m.schema->data, m.schema->name,
        "channel " + m.channel->topic + " (schema " + m.schema->name + ")");
    e.name = m.schema->name;
    e.data = m.schema->data;
  }
  return e.decoder->ToJson(m.data);
}

}  // namespace mrsim::mcap
