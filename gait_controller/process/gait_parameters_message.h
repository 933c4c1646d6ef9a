// The seven gait parameters as gait_command_t and gait_status_t carry them
// (`double parameters[7]`): the one place that converts between the
// message array and GaitParameters. The array's size is checked against
// GaitParameters::kVectorSize at compile time, so a change to either side
// fails the build instead of silently copying too few or too many values.
#pragma once

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "gait_controller/gait_parameters.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"

namespace mrsim {

static_assert(std::extent_v<decltype(gait_command_t::parameters)> ==
                  GaitParameters::kVectorSize,
              "gait_command_t.parameters must hold the gait's vector");
static_assert(std::extent_v<decltype(gait_status_t::parameters)> ==
                  GaitParameters::kVectorSize,
              "gait_status_t.parameters must hold the gait's vector");

// A message's parameter array, by reference so the size is part of the type.
using GaitParameterArray = double[GaitParameters::kVectorSize];

// The seven values of a message, in GaitParameters::ToVector order.
inline std::vector<double> GaitParameterValues(const GaitParameterArray& in) {
  return std::vector<double>(std::begin(in), std::end(in));
}

// The message's seven values as GaitParameters (lag 0, no overrides; the
// values are not checked: use ValidateGaitParameters).
inline GaitParameters GaitParametersFromMessage(const GaitParameterArray& in) {
  return GaitParameters::FromVector(GaitParameterValues(in));
}

// Writes the seven values of `parameters` into a message's array.
inline void WriteGaitParameters(const GaitParameters& parameters,
                                GaitParameterArray& out) {
  const std::array<double, GaitParameters::kVectorSize> values =
      parameters.ToArray();
  std::copy(values.begin(), values.end(), std::begin(out));
}

}  // namespace mrsim
