// A valid encoding of any message type, built from its .lcm definition (the
// logger's registry) rather than from lcm-gen's code, with where each length
// field sits: the wire-check tests forge every length of every type with it,
// types added later included.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "logger/lcm_type_registry.h"

namespace mrsim::testing {

struct LengthField {
  std::string name;     // "robot_state_t.sensor_modules.num_distances"
  size_t offset = 0;    // of the length's first byte
  size_t bytes = 0;     // its width: 1, 2, 4 or 8
  bool string = false;  // a string's length (counts the NUL), else a count
};

struct WireSample {
  std::vector<uint8_t> bytes;
  std::vector<LengthField> lengths;
};

// Every variable array holds `count` elements, every string "ab".
WireSample BuildWireSample(const LcmTypeRegistry& registry,
                           const LcmStruct& type, int64_t fingerprint,
                           int count = 2);

// Writes `value` big-endian over the `width` bytes at `offset`.
void PutBigEndian(std::vector<uint8_t>* bytes, size_t offset, size_t width,
                  int64_t value);

}  // namespace mrsim::testing
