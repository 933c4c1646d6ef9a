// IMU readings through the codec and the logger's flattener: named columns
// from the sensor kinds' table, values exact.
#include <gtest/gtest.h>

#include <charconv>
#include <vector>

#include "logger/lcm_type_registry.h"
#include "logger/robot_state_flattener.h"
#include "sim_core/codec/state_message.h"
#include "tests/logger/csv_reader.h"

namespace mrsim {
namespace {

RobotState StateWithImu() {
  RobotState state;
  state.time = 1.5;
  state.robot = "probe";
  SensorModuleState sm;
  sm.has_force = true;
  sm.force = 2.5;
  sm.distances = {0.75};
  sm.distance_faces = {4};
  sm.readings.push_back({"imu", -1, {0.1, -0.2, 9.81, 0.01, 0.02, 2.0}});
  state.sensor_modules.push_back(sm);
  return state;
}

std::vector<uint8_t> Encode(const robot_state_t& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

TEST(CodecImu, ReadingsSurviveTheMessage) {
  const RobotState state = StateWithImu();
  const RobotState back = FromRobotStateMessage(ToRobotStateMessage(state, 3));
  ASSERT_EQ(back.sensor_modules.size(), 1u);
  ASSERT_EQ(back.sensor_modules[0].readings.size(), 1u);
  const SensorReading& r = back.sensor_modules[0].readings[0];
  EXPECT_EQ(r.kind, "imu");
  EXPECT_EQ(r.face, -1);
  EXPECT_EQ(r.values, state.sensor_modules[0].readings[0].values);
}

TEST(LoggerFlatten, ImuReadingsAreColumnsNamedByTheKindsTable) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  const auto bytes = Encode(ToRobotStateMessage(StateWithImu(), 3));
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  const auto& cols = flattener.columns();
  const auto cells = testing::SplitCsvLine(row.values);
  ASSERT_EQ(cells.size(), cols.size());
  auto cell = [&](const std::string& name) {
    for (size_t i = 0; i < cols.size(); ++i) {
      if (cols[i] == name) {
        double v = 0;
        std::from_chars(cells[i].data(), cells[i].data() + cells[i].size(), v);
        return v;
      }
    }
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  EXPECT_EQ(cell("sensor_module0.force"), 2.5);
  EXPECT_EQ(cell("sensor_module0.distance4"), 0.75);
  EXPECT_EQ(cell("sensor_module0.imu.accel.x"), 0.1);
  EXPECT_EQ(cell("sensor_module0.imu.accel.z"), 9.81);
  EXPECT_EQ(cell("sensor_module0.imu.gyro.z"), 2.0);
}

TEST(LoggerFlatten, ReadingOfAnUnknownKindIsNamedByPosition) {
  RobotState state = StateWithImu();
  state.sensor_modules[0].readings[0].kind = "sonar,\"x";
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  const auto bytes = Encode(ToRobotStateMessage(state, 3));
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  const auto& cols = flattener.columns();
  EXPECT_NE(std::find(cols.begin(), cols.end(), "sensor_module0.reading0.5"),
            cols.end());
  for (const std::string& c : cols) {
    EXPECT_EQ(c.find("sonar"), std::string::npos) << c;
  }
}

}  // namespace
}  // namespace mrsim
