// Flattens any message type known from its .lcm definition. Columns are
// named by member path: `time` (s, from a top-level int64 utime), `seq`,
// `target3` (array element), `sensor_modules0.force` (struct member),
// pose_t members as `.x .y .z .qw .qx .qy .qz`, double[3] as `.x .y .z`.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "logger/lcm_type_registry.h"
#include "logger/message_flattener.h"

namespace mrsim {

class GenericFlattener : public MessageFlattener {
 public:
  // `registry` must outlive the flattener.
  GenericFlattener(const LcmTypeRegistry& registry, const LcmStruct& type);
  bool Flatten(const uint8_t* data, size_t size, FlatRow* row) override;
  std::string type_name() const override { return type_.full_name(); }

  // True when `body` (a message after its 8-byte fingerprint) is exactly
  // one well-formed encoding of `type`: non-negative array lengths that fit
  // in the bytes, NUL-terminated strings, nothing left over.
  static bool IsWellFormedBody(const LcmTypeRegistry& registry,
                               const LcmStruct& type, const uint8_t* body,
                               size_t size);

 private:
  const LcmTypeRegistry& registry_;
  const LcmStruct& type_;
  int64_t fingerprint_;
  std::vector<int64_t> last_shape_;
  bool have_shape_ = false;
};

}  // namespace mrsim
