// Units of the columns mrsim-log writes, end to end: a scenario whose
// sensor module carries every sensor kind of SensorKinds() is simulated by
// mrsim-sim and logged by mrsim-log; every column of the CSV has its unit
// from the tables (the .lcm files' `// unit:` comments, the kinds'
// channels), and the IMU's columns plot in m/s^2 and rad/s.
#include "logger/column_units.h"

#include <gtest/gtest.h>

#include <string>

#include "logger/plot.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/scenario/sensor_kind.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/logger/csv_reader.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::SourcePath;
using testing::TempDir;
using testing::TestLcmUrl;

// imu_snake's first sensor module with one sensor of every kind. A kind
// added later that this cannot put on fails here: add it below.
Scenario EverySensorKind() {
  Scenario s = ReadScenarioFile(SourcePath("scenarios/imu_snake.xml"));
  SensorModule& sm = s.robots.at(0).sensor_modules.at(0);
  for (const SensorKind& kind : SensorKinds()) {
    if (kind.count(sm) > 0) continue;
    if (kind.set != nullptr) {
      kind.set(sm, true);
      // The force plate on the top face: on the bottom it would start in
      // the ground.
      if (sm.force_sensor) sm.force_sensor->sensor_position = 2;
    } else if (std::string(kind.member) == "distance_sensors") {
      DistanceSensor ds;
      ds.guid = sm.guid + "/distance4";
      ds.sensor_position = 4;
      sm.distance_sensors.push_back(ds);
    } else if (std::string(kind.member) == "cameras") {
      sm.cameras.emplace_back();  // no columns: its pictures are files
    }
    EXPECT_GT(kind.count(sm), 0) << "no " << kind.name << " on the module";
  }
  return s;
}

TEST(ColumnUnits, EveryLoggedColumnOfEverySensorKindHasAUnitFromTheTables) {
  const std::string dir = TempDir("column_units");
  const std::string url = TestLcmUrl(7761);
  const Scenario s = EverySensorKind();
  const std::string scenario = dir + "/every_kind.xml";
  WriteScenarioFile(s, scenario);
  const std::string robot = s.robots[0].name;

  ChildProcess logger({BinaryPath("logger/process/mrsim-log"), "--lcm-url", url,
                       "--out", dir + "/csv"},
                      dir + "/log.txt");
  ASSERT_TRUE(logger.WaitForOutput("recording channels", 60))
      << logger.Output();
  ChildProcess sim(
      {BinaryPath("sim_core/sim_process/mrsim-sim"), scenario, "--lcm-url", url,
       "--clock", "fast", "--rate", "50", "--duration", "0.5"},
      dir + "/sim.txt");
  EXPECT_EQ(sim.Wait(120), 0) << sim.Output();
  const std::string csv = dir + "/csv/MRSIM_STATE_" + robot + ".csv";
  ASSERT_TRUE(testing::WaitForLines(csv, 10, 60)) << logger.Output();
  EXPECT_EQ(logger.Stop(), 0) << logger.Output();

  const testing::CsvFile f = testing::ReadCsvFile(csv);
  ASSERT_GT(f.header.size(), 20u);
  for (const std::string& column : f.header) {
    EXPECT_TRUE(FindColumnUnit(column).has_value())
        << column << " has no unit in the tables";
  }
  // Each kind's values carry its channels' units.
  const SensorModule& sm = s.robots[0].sensor_modules[0];
  for (const SensorKind& kind : SensorKinds()) {
    for (const SensorChannel& channel : kind.channels) {
      const int face =
          kind.store != nullptr && !kind.many ? -1 : kind.face(sm, 0);
      const std::string column =
          SensorValueName("sensor_module0", kind, face, channel);
      EXPECT_GE(f.Column(column), 0) << column << " was not logged";
      EXPECT_EQ(FindColumnUnit(column), std::string(channel.unit)) << column;
    }
  }
  EXPECT_EQ(ColumnUnit("sensor_module0.imu.accel.x"), "m/s^2");
  EXPECT_EQ(ColumnUnit("sensor_module0.imu.gyro.z"), "rad/s");

  // The plot's axes: the accelerometer shares one in m/s^2, the gyro is in
  // rad/s, and accelerations never share an axis with positions.
  PlotOptions accel;
  accel.y = {"sensor_module0.imu.accel.x", "sensor_module0.imu.accel.y",
             "sensor_module0.imu.accel.z"};
  EXPECT_EQ(PlotCsvToPng(csv, accel, dir + "/accel.png").y.label,
            "value [m/s^2]");
  PlotOptions gyro;
  gyro.y = {"sensor_module0.imu.gyro.z"};
  EXPECT_EQ(PlotCsvToPng(csv, gyro, dir + "/gyro.png").y.label,
            "sensor_module0.imu.gyro.z [rad/s]");
  PlotOptions mixed;
  mixed.y = {"sensor_module0.imu.accel.x", "module0.x"};
  EXPECT_EQ(PlotCsvToPng(csv, mixed, dir + "/mixed.png").y.label, "value");
}

TEST(ColumnUnits, NamesOutsideTheTablesHaveNoUnit) {
  // Once guessed from the last word: metres for any `.x`, newtons for any
  // `force`. Only columns of the tables have units now.
  EXPECT_EQ(FindColumnUnit("foo.x"), std::nullopt);
  EXPECT_EQ(FindColumnUnit("fitness.force"), std::nullopt);
  EXPECT_EQ(FindColumnUnit("sensor_module0.sonar.range"), std::nullopt);
  EXPECT_EQ(FindColumnUnit("module3.joint.torque"), "N m");
  EXPECT_EQ(FindColumnUnit("module3.frame1.qz"), "1");
  EXPECT_EQ(FindColumnUnit("sensor_module2.distance4_1"), "m");
  EXPECT_EQ(FindColumnUnit("lock.snake/lock3.attached"), "1");
  EXPECT_EQ(ColumnLabel("orientation.qx"), "orientation.qx");
}

}  // namespace
}  // namespace mrsim
