// The loose parts' state (robot_state_t of the owner "loose", published by
// mrsim-sim on <prefix>_STATE_loose) through the codec and the logger's
// flattener: a column per loose frame, hinge and sensor module, with units.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "logger/column_units.h"
#include "logger/lcm_type_registry.h"
#include "logger/robot_state_flattener.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/scenario/scenario.h"
#include "tests/logger/csv_reader.h"

namespace mrsim {
namespace {

// As Physics::ReadLooseState gives it: two loose frames, the hinge
// between them, one loose sensor module with an IMU; no modules.
RobotState LooseState() {
  RobotState state;
  state.time = 0.5;
  state.robot = kLooseOwnerName;
  Pose frame;
  frame.position = Eigen::Vector3d(0.1, 1.0, 0.025);
  state.frames = {frame, frame};
  state.frames[1].position.x() = 0.05;
  JointState hinge;
  hinge.angle = 0.3;
  hinge.speed = -0.5;
  state.joints.push_back(hinge);
  SensorModuleState sm;
  sm.pose.position = Eigen::Vector3d(0, -1.0, 0.025);
  sm.readings.push_back({"imu", -1, {0, 0, 9.81, 0, 0, 0}});
  state.sensor_modules.push_back(sm);
  return state;
}

TEST(LoggerFlatten, LoosePartsAreColumnsPerFrameHingeAndSensorModule) {
  const robot_state_t msg = ToRobotStateMessage(LooseState(), 7);
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  const std::vector<std::string>& cols = flattener.columns();
  const std::vector<std::string> cells = testing::SplitCsvLine(row.values);
  ASSERT_EQ(cells.size(), cols.size());
  auto cell = [&](const std::string& name) -> std::string {
    for (size_t i = 0; i < cols.size(); ++i) {
      if (cols[i] == name) return cells[i];
    }
    ADD_FAILURE() << "no column " << name;
    return "";
  };
  EXPECT_EQ(cell("robot"), "loose");
  EXPECT_EQ(cell("frame0.x"), "0.1");
  EXPECT_EQ(cell("frame1.x"), "0.05");
  EXPECT_EQ(cell("frame1.z"), "0.025");
  EXPECT_EQ(cell("joint0.angle"), "0.3");
  EXPECT_EQ(cell("joint0.speed"), "-0.5");
  EXPECT_EQ(cell("sensor_module0.y"), "-1");
  EXPECT_EQ(cell("sensor_module0.imu.accel.z"), "9.81");
  for (const std::string& c : cols) {
    EXPECT_EQ(c.rfind("module", 0), std::string::npos) << c;  // no modules
  }
  // Units as the other channels', from the .lcm and the kinds' table.
  EXPECT_EQ(ColumnUnit("frame1.z"), "m");
  EXPECT_EQ(ColumnUnit("joint0.angle"), "rad");
  EXPECT_EQ(ColumnUnit("joint0.speed"), "rad/s");
  EXPECT_EQ(ColumnUnit("sensor_module0.imu.accel.z"), "m/s^2");
}

}  // namespace
}  // namespace mrsim
