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
  // Compiles the type's layout; the registry is not needed afterwards.
  GenericFlattener(const LcmTypeRegistry& registry, const LcmStruct& type);
  ~GenericFlattener() override;
  bool Flatten(const uint8_t* data, size_t size, FlatRow* row) override;
  std::string type_name() const override { return type_name_; }

  // True when `data` is exactly one well-formed message of this type: its
  // fingerprint, non-negative array lengths that fit in the bytes,
  // NUL-terminated strings, nothing left over.
  bool IsWellFormed(const uint8_t* data, size_t size) const;

  struct Layout;  // the compiled type, defined in the .cc

 private:
  std::string type_name_;
  int64_t fingerprint_;
  std::vector<std::unique_ptr<Layout>> layouts_;  // [0] is the type itself
  std::vector<int64_t> shape_;
  std::vector<int64_t> last_shape_;
  bool have_shape_ = false;
};

}  // namespace mrsim
