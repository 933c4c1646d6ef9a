// Turns an encoded LCM message straight into protobuf wire format, walking
// the type's layout from its .lcm definition (no generated code, no
// protobuf reflection): the payload of mrsim-log --mcap's protobuf
// channels, whose schema is LcmProtobufDescriptorSet's. It is the logger's
// CPU path, so it writes varints and little-endian numbers itself. Scalars
// that are zero are left out (proto3: readers see the default, 0), nested
// structs are always written; strings are made valid UTF-8 as the JSON
// encoding makes them (a byte that is not becomes U+FFFD), since proto3
// readers refuse a string that is not.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "logger/lcm_type_registry.h"

namespace mrsim {

class LcmProtobufEncoder {
 public:
  // Compiles the layout of `type`; the registry is not needed afterwards.
  // Throws std::runtime_error when a member's type is not in the registry.
  LcmProtobufEncoder(const LcmTypeRegistry& registry, const LcmStruct& type);
  ~LcmProtobufEncoder();
  LcmProtobufEncoder(const LcmProtobufEncoder&) = delete;
  LcmProtobufEncoder& operator=(const LcmProtobufEncoder&) = delete;

  // Encodes one LCM message (fingerprint first) into view(). False, with
  // view() not to be used, unless `data` is exactly one well-formed message
  // of the type: its fingerprint, array lengths from 0 that fit in the
  // bytes, NUL-terminated strings, nothing left over, nesting at most
  // kMaxDepth deep.
  bool Encode(const uint8_t* data, size_t size);
  std::string_view view() const { return {buf_.data(), size_}; }
  // Of the last message encoded: whether it has a top-level int64_t seq,
  // and its value.
  bool has_seq() const { return has_seq_; }
  int64_t seq() const { return seq_; }

  int64_t fingerprint() const { return fingerprint_; }
  const std::string& type_name() const { return type_name_; }

  static constexpr int kMaxDepth = 64;

  struct Layout;  // the compiled type, defined in the .cc

 private:
  std::string type_name_;
  int64_t fingerprint_ = 0;
  std::vector<std::unique_ptr<Layout>> layouts_;  // [0] is the type itself
  std::string buf_;
  size_t size_ = 0;
  bool has_seq_ = false;
  int64_t seq_ = 0;
};

}  // namespace mrsim
