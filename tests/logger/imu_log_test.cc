// End to end: a sensor module's IMU simulated by mrsim-sim, published on
// LCM and logged by mrsim-log as CSV columns, at rest reading gravity; a
// loose sensor module (no robot) dropped beside it, logged from
// <prefix>_STATE_loose where it landed.
#include <gtest/gtest.h>

#include <charconv>
#include <string>

#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/logger/csv_reader.h"

namespace mrsim {
namespace {

using testing::BinaryPath;
using testing::ChildProcess;
using testing::TempDir;
using testing::TestLcmUrl;

TEST(ImuEndToEnd, SimulatedPublishedAndLoggedAsCsvColumns) {
  const std::string dir = TempDir("imu_log");
  const std::string url = TestLcmUrl(7760);
  Scenario s;
  Robot robot;
  robot.name = "probe";
  SensorModule sm;
  sm.guid = "sm0";
  sm.position = Eigen::Vector3d(0, 0, 0.025);
  sm.imu = Imu{};
  robot.sensor_modules.push_back(sm);
  s.robots.push_back(robot);
  SensorModule loose = sm;
  loose.guid = "loose eye";
  loose.position = Eigen::Vector3d(0, 1.0, 0.2);
  s.loose_sensor_modules.push_back(loose);
  const std::string scenario = dir + "/imu.xml";
  WriteScenarioFile(s, scenario);

  ChildProcess logger({BinaryPath("logger/process/mrsim-log"), "--lcm-url", url,
                       "--out", dir + "/csv"},
                      dir + "/log.txt");
  ASSERT_TRUE(logger.WaitForOutput("recording channels", 60))
      << logger.Output();
  ChildProcess sim(
      {BinaryPath("sim_core/sim_process/mrsim-sim"), scenario, "--lcm-url", url,
       "--clock", "fast", "--rate", "50", "--duration", "2"},
      dir + "/sim.txt");
  EXPECT_EQ(sim.Wait(120), 0) << sim.Output();
  const std::string csv = dir + "/csv/MRSIM_STATE_probe.csv";
  // 2 s at 50 Hz: about 100 rows; the last ones settled on the ground.
  ASSERT_TRUE(testing::WaitForLines(csv, 50, 60)) << logger.Output();
  EXPECT_EQ(logger.Stop(), 0) << logger.Output();

  const testing::CsvFile f = testing::ReadCsvFile(csv);
  const int z = f.Column("sensor_module0.imu.accel.z");
  const int gx = f.Column("sensor_module0.imu.gyro.x");
  ASSERT_GE(z, 0) << f.text.substr(0, 2000);
  ASSERT_GE(gx, 0);
  ASSERT_FALSE(f.rows.empty());
  const std::vector<std::string>& last = f.rows.back();
  double accel_z = 0;
  double gyro_x = 1;
  std::from_chars(last[z].data(), last[z].data() + last[z].size(), accel_z);
  std::from_chars(last[gx].data(), last[gx].data() + last[gx].size(), gyro_x);
  EXPECT_NEAR(accel_z, 9.81, 0.1);
  EXPECT_NEAR(gyro_x, 0.0, 0.01);

  // The loose module fell from 0.2 m and lies on the ground, reading
  // gravity: its pose and readings are in the log, not the scenario's.
  const testing::CsvFile loose_csv =
      testing::ReadCsvFile(dir + "/csv/MRSIM_STATE_loose.csv");
  const int lz = loose_csv.Column("sensor_module0.z");
  const int laz = loose_csv.Column("sensor_module0.imu.accel.z");
  ASSERT_GE(lz, 0) << loose_csv.text.substr(0, 2000);
  ASSERT_GE(laz, 0);
  ASSERT_GE(loose_csv.rows.size(), 50u);
  const std::vector<std::string>& landed = loose_csv.rows.back();
  double loose_z = 1;
  double loose_accel_z = 0;
  std::from_chars(landed[lz].data(), landed[lz].data() + landed[lz].size(),
                  loose_z);
  std::from_chars(landed[laz].data(), landed[laz].data() + landed[laz].size(),
                  loose_accel_z);
  EXPECT_NEAR(loose_z, 0.025, 0.005);
  EXPECT_NEAR(loose_accel_z, 9.81, 0.1);
}

}  // namespace
}  // namespace mrsim
