#include "logger/column_units.h"

namespace mrsim {

std::string ColumnUnit(const std::string& column) {
  const size_t dot = column.rfind('.');
  const std::string last =
      dot == std::string::npos ? column : column.substr(dot + 1);
  if (column == "time" || column == "sim_time") return "s";
  if (column.rfind("com_velocity.", 0) == 0) return "m/s";
  if (column == "heading") return "rad";
  if (last == "x" || last == "y" || last == "z") return "m";
  if (last == "angle") return "rad";
  if (last == "speed") return "rad/s";
  if (last == "torque") return "N m";
  if (last == "force") return "N";
  if (last.rfind("distance", 0) == 0 && last != "distance_face") return "m";
  if (column.rfind("target", 0) == 0) return "rad";
  return "";
}

std::string ColumnLabel(const std::string& column) {
  const std::string unit = ColumnUnit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

}  // namespace mrsim
