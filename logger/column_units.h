// The unit of each column mrsim-log writes for robot states, for axis
// labels and for which columns share a plot axis. Units are declared once:
// message fields by their `// unit:` comment in lcmtypes/mrsim/*.lcm
// (mrsim/field_units.hpp, generated), sensor values by their kind's
// channels (sim_core's SensorKinds()). A column is resolved by where the
// flattener (robot_state_flattener.h) puts it, `module3.joint.torque` is
// joint_state_t.torque, `sensor_module0.imu.accel.x` the IMU's accel.x
// channel, never by the look of its last word.
#pragma once

#include <optional>
#include <string>

namespace mrsim {

// The column's unit from the tables: "m", "rad/s", "1" for a number
// without a unit, "" for text (`robot`); nullopt for a column that is not
// one mrsim-log writes for a robot state (another CSV's, or a sensor kind
// this build does not know).
std::optional<std::string> FindColumnUnit(const std::string& column);
// The unit an axis shows: FindColumnUnit's, "" for none, text, "1" or an
// unknown column.
std::string ColumnUnit(const std::string& column);
// "name [unit]", or the name alone when the unit is empty.
std::string ColumnLabel(const std::string& column);

}  // namespace mrsim
