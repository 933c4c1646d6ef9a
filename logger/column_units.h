// SI unit of a logger column, from its name (`module3.z` is in m,
// `module3.joint.torque` in N m), for axis labels.
#pragma once

#include <string>

namespace mrsim {

// The unit ("m", "rad/s", ...) or "" for unitless or unknown columns.
std::string ColumnUnit(const std::string& column);
// "name [unit]", or the name alone when the unit is empty.
std::string ColumnLabel(const std::string& column);

}  // namespace mrsim
