// How far a new measurement of an atlas line is from the table, quantity by
// quantity, and the message that tells a developer what moved and what to
// do about it (regenerate the table, say why in docs/physics.md).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gait_controller/atlas_table.h"

namespace mrsim {

struct AtlasDeviation {
  std::string line;
  AtlasQuantity quantity = AtlasQuantity::kSpeed;
  double expected = 0.0;  // the table's value
  double measured = 0.0;
  double tolerance = 0.0;  // the table's
  bool beyond = false;     // |measured - expected| > tolerance
};

// One deviation per quantity of `expected`, in AtlasQuantity order.
std::vector<AtlasDeviation> CompareAtlasLine(
    const AtlasLine& expected,
    const std::array<double, kAtlasQuantities>& measured);

// True when any deviation is beyond its tolerance.
bool AnyBeyond(const std::vector<AtlasDeviation>& deviations);

// For the deviations beyond tolerance: "gait atlas line 'forward' moved:
// speed 0.0230 -> 0.0260 bl/s (+0.0030, +13.0 %; tolerance 0.0008) ..."
// and how to regenerate the table; "" when none is beyond.
std::string DescribeAtlasDeviations(
    const std::vector<AtlasDeviation>& deviations);

}  // namespace mrsim
