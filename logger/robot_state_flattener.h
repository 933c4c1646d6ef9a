// Flattens mrsim::robot_state_t with the names users plot by: `time`, `seq`,
// `robot`, `sim_time`, `module3.x .. module3.qz`, `module3.frame0.x ..`,
// `module3.joint.angle/speed/torque/x..qz`, `sensor_module0.x ..`,
// `sensor_module0.force`, `sensor_module0.distance4` (4 = face),
// `sensor_module0.imu.accel.x` (the sensor kinds' table, sensor_kind.h),
// `com.x`, `com_velocity.x`, `orientation.qw .. qz`, `heading`,
// `lock.snake/lock3.attached` (1 holds, 0 released).
// SI units throughout.
#pragma once

#include <string>
#include <vector>

#include "logger/generic_flattener.h"
#include "logger/lcm_type_registry.h"
#include "logger/message_flattener.h"
#include "mrsim/robot_state_t.hpp"
#include "sim_core/scenario/sensor_kind.h"

namespace mrsim {

class RobotStateFlattener : public MessageFlattener {
 public:
  // Throws when `registry` lacks mrsim.robot_state_t or it differs from
  // the compiled type.
  explicit RobotStateFlattener(const LcmTypeRegistry& registry);
  bool Flatten(const uint8_t* data, size_t size, FlatRow* row) override;
  std::string type_name() const override { return "mrsim.robot_state_t"; }

 private:
  std::vector<std::string> ColumnNames() const;

  robot_state_t msg_;
  std::vector<int> shape_;
  std::vector<int> last_shape_;
  std::vector<std::string> last_locks_;
  bool have_shape_ = false;
  // Kinds in the shape by index in SensorKinds().
  const SensorKind* kinds_base_ = SensorKinds().data();
};

}  // namespace mrsim
