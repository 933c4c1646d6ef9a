#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <vector>

#include "logger/column_units.h"
#include "logger/generic_flattener.h"
#include "logger/lcm_type_registry.h"
#include "logger/robot_state_flattener.h"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tests/logger/csv_reader.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

template <typename T>
std::vector<uint8_t> Encode(const T& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

double Parse(const std::string& s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  EXPECT_EQ(r.ptr, s.data() + s.size()) << s;
  return v;
}

TEST(LoggerFlatten, RobotStateColumnsAreNamedAndValuesExact) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  const robot_state_t msg = testing::KnownRobotState(42, 5, 2);
  const auto bytes = Encode(msg);
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  EXPECT_TRUE(row.has_seq);
  EXPECT_EQ(row.seq, 42);

  const auto& cols = flattener.columns();
  const auto cells = testing::SplitCsvLine(row.values);
  ASSERT_EQ(cells.size(), cols.size());
  auto cell = [&](const std::string& name) -> std::string {
    for (size_t i = 0; i < cols.size(); ++i) {
      if (cols[i] == name) return cells[i];
    }
    ADD_FAILURE() << "no column " << name;
    return "0";
  };
  EXPECT_EQ(cols[0], "time");
  EXPECT_EQ(Parse(cell("time")), 0.042017);
  EXPECT_EQ(cell("seq"), "42");
  EXPECT_EQ(cell("robot"), "snake");
  EXPECT_EQ(Parse(cell("module3.z")), msg.modules[3].position[2]);
  EXPECT_EQ(Parse(cell("module3.qw")), msg.modules[3].orientation[0]);
  EXPECT_EQ(Parse(cell("module3.frame1.qz")), msg.frames[7].orientation[3]);
  EXPECT_EQ(Parse(cell("module3.joint.angle")), msg.joints[3].angle);
  EXPECT_EQ(Parse(cell("module3.joint.speed")), msg.joints[3].speed);
  EXPECT_EQ(Parse(cell("module3.joint.torque")), msg.joints[3].torque);
  EXPECT_EQ(Parse(cell("sensor_module1.force")), msg.sensor_modules[1].force);
  EXPECT_EQ(Parse(cell("sensor_module0.distance0")),
            msg.sensor_modules[0].distance[0]);
  EXPECT_EQ(Parse(cell("sensor_module0.distance4")),
            msg.sensor_modules[0].distance[1]);
  EXPECT_EQ(Parse(cell("com.x")), msg.com[0]);
  EXPECT_EQ(Parse(cell("com_velocity.z")), msg.com_velocity[2]);
  EXPECT_EQ(cell("lock.snake/lock0.attached"), "1");
  EXPECT_EQ(cell("lock.snake/lock3.attached"), "0");
  EXPECT_EQ(cols.back(), "lock.snake/lock3.attached");
}

// The orientation columns come right after the centre of mass, so every
// column a script already reads keeps its name.
TEST(LoggerFlatten, RobotOrientationColumnsFollowTheCentreOfMass) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  const robot_state_t msg = testing::KnownRobotState(7, 3, 0);
  const auto bytes = Encode(msg);
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  const auto& cols = flattener.columns();
  const auto cells = testing::SplitCsvLine(row.values);
  ASSERT_EQ(cells.size(), cols.size());
  const auto at = std::find(cols.begin(), cols.end(), "com_velocity.z");
  ASSERT_NE(at, cols.end());
  const size_t i = static_cast<size_t>(at - cols.begin()) + 1;
  ASSERT_LE(i + 5, cols.size());
  const std::vector<std::string> want = {"orientation.qw", "orientation.qx",
                                         "orientation.qy", "orientation.qz",
                                         "heading"};
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_EQ(cols[i + k], want[k]);
    const double value = k < 4 ? msg.orientation[k] : msg.heading;
    EXPECT_EQ(Parse(cells[i + k]), value) << want[k];
  }
  EXPECT_EQ(ColumnUnit("heading"), "rad");
  EXPECT_EQ(ColumnUnit("orientation.qx"), "");
}

TEST(LoggerFlatten, RenamedLocksGetNewColumns) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  FlatRow row;
  auto a = Encode(testing::KnownRobotState(0, 3, 0, "snake"));
  auto b = Encode(testing::KnownRobotState(1, 3, 0, "worm"));
  ASSERT_TRUE(flattener.Flatten(a.data(), a.size(), &row));
  const uint64_t v1 = flattener.shape_version();
  ASSERT_TRUE(flattener.Flatten(b.data(), b.size(), &row));
  EXPECT_NE(flattener.shape_version(), v1);
  EXPECT_EQ(flattener.columns().back(), "lock.worm/lock1.attached");
}

TEST(LoggerFlatten, ShapeChangeBumpsTheColumnVersion) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  FlatRow row;
  auto a = Encode(testing::KnownRobotState(0, 3, 1));
  auto b = Encode(testing::KnownRobotState(1, 3, 1));
  auto c = Encode(testing::KnownRobotState(2, 4, 1));
  ASSERT_TRUE(flattener.Flatten(a.data(), a.size(), &row));
  const uint64_t v1 = flattener.shape_version();
  ASSERT_TRUE(flattener.Flatten(b.data(), b.size(), &row));
  EXPECT_EQ(flattener.shape_version(), v1);
  ASSERT_TRUE(flattener.Flatten(c.data(), c.size(), &row));
  EXPECT_NE(flattener.shape_version(), v1);
}

TEST(LoggerFlatten, ForgedArrayLengthIsRejectedNotTrusted) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener flattener(registry);
  auto bytes = Encode(testing::KnownRobotState(0, 2, 0));
  // num_modules is the first big-endian int32 2 after the robot's name.
  const uint8_t two[4] = {0, 0, 0, 2};
  const size_t name_end = 8 + 8 + 8 + 4 + std::strlen("snake") + 1;
  const auto at = std::search(bytes.begin() + name_end, bytes.end(),
                              std::begin(two), std::end(two));
  ASSERT_NE(at, bytes.end());
  *at = 0x7f;  // about 2^31 modules
  FlatRow row;
  EXPECT_FALSE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  auto truncated = Encode(testing::KnownRobotState(0, 2, 0));
  truncated.pop_back();
  EXPECT_FALSE(flattener.Flatten(truncated.data(), truncated.size(), &row));
  auto longer = Encode(testing::KnownRobotState(0, 2, 0));
  longer.push_back(0);
  EXPECT_FALSE(flattener.Flatten(longer.data(), longer.size(), &row));
}

TEST(LoggerFlatten, GenericTypeGetsTimeSeqAndNamedCells) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  GenericFlattener flattener(registry,
                             *registry.FindByName("mrsim.sim_status_t"));
  sim_status_t st{};
  st.utime = 2500000;
  st.seq = 7;
  st.sim_time = 0.1 + 0.2;
  st.real_time_factor = 1.0 / 3.0;
  st.mode = sim_status_t::PAUSED;
  st.clock = "fast";
  st.steps = 1234;
  st.last_error = "bad \"joint\", index 3";
  st.instance = "host:42";
  const auto bytes = Encode(st);
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  EXPECT_TRUE(row.has_seq);
  EXPECT_EQ(row.seq, 7);
  const auto& cols = flattener.columns();
  // Quoted text holds commas, so split by the columns' known order.
  const std::string expected_start =
      "2.5,7,0.30000000000000004,0.3333333333333333,1,fast,";
  EXPECT_EQ(row.values.substr(0, expected_start.size()), expected_start);
  const std::vector<std::string> first_cols = {
      "time", "seq", "sim_time", "real_time_factor", "mode", "clock"};
  EXPECT_EQ(std::vector<std::string>(cols.begin(), cols.begin() + 6),
            first_cols);
  EXPECT_EQ(cols.back(), "instance");
  EXPECT_EQ(cols[cols.size() - 2], "last_error");
  const std::string quoted = "\"bad \"\"joint\"\", index 3\",host:42";
  EXPECT_EQ(row.values.substr(row.values.size() - quoted.size()), quoted);
  EXPECT_NE(std::find(cols.begin(), cols.end(), "steps"), cols.end());
  EXPECT_NE(row.values.find(",1234,"), std::string::npos);
}

TEST(LoggerFlatten, RobotStateHasAColumnForEveryField) {
  // Guards against a field added to robot_state_t.lcm but not to the
  // named flattener: both must carry the same data.
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  RobotStateFlattener named(registry);
  GenericFlattener generic(registry,
                           *registry.FindByName("mrsim.robot_state_t"));
  const auto bytes = Encode(testing::KnownRobotState(3, 4, 2));
  FlatRow a, b;
  ASSERT_TRUE(named.Flatten(bytes.data(), bytes.size(), &a));
  ASSERT_TRUE(generic.Flatten(bytes.data(), bytes.size(), &b));
  size_t counts = 0;  // array lengths, flags and faces are in the names
  for (const std::string& c : generic.columns()) {
    if (c.rfind("num_", 0) == 0 || c.find(".num_") != std::string::npos ||
        c.find("has_force") != std::string::npos ||
        c.rfind("lock_names", 0) == 0 ||
        c.find("distance_face") != std::string::npos) {
      ++counts;
    }
  }
  EXPECT_EQ(named.columns().size(), generic.columns().size() - counts);
}

TEST(LoggerFlatten, GenericArraysAreIndexed) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  GenericFlattener flattener(registry,
                             *registry.FindByName("mrsim.joint_command_t"));
  joint_command_t cmd;
  cmd.utime = 1;
  cmd.seq = 3;
  cmd.robot = "r";
  cmd.sender = "s";
  cmd.state_seq = 2;
  cmd.num_joints = 3;
  cmd.target = {0.5, -1e-300, 7};
  const auto bytes = Encode(cmd);
  FlatRow row;
  ASSERT_TRUE(flattener.Flatten(bytes.data(), bytes.size(), &row));
  const std::vector<std::string> expected_cols = {
      "time",       "seq",     "robot",   "sender", "state_seq",
      "num_joints", "target0", "target1", "target2"};
  EXPECT_EQ(flattener.columns(), expected_cols);
  EXPECT_EQ(row.values, "1e-06,3,r,s,2,3,0.5,-1e-300,7");
}

}  // namespace
}  // namespace mrsim
