// The pure parts of the sim bridge: state messages and the command rules.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lcmtypes/runtime/usage_error.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/sim_process/command_filter.h"
#include "sim_core/sim_process/sim_command_line.h"
#include "tests/common/child_process.h"
#include "tests/common/parse_flags.h"

namespace mrsim {
namespace {

TEST(SimProcessStateMessage, ElevenModuleStateIsFarBelowOneFragment) {
  Scenario scenario;
  ChainOptions options;
  options.modules = 11;
  options.sensor_after = {-1, 5};
  options.force_sensors = true;
  options.front_distance_sensor = true;
  scenario.robots.push_back(MakeChain(options));
  Physics physics(scenario);
  physics.Step(10);
  const robot_state_t msg = ToRobotStateMessage(physics.ReadRobotState(0), 3);
  EXPECT_EQ(msg.num_joints, 11);
  EXPECT_EQ(msg.num_frames, 22);
  EXPECT_EQ(msg.num_sensor_modules, 2);
  // LCM fragments messages above ~64 KB and loses them whole when one
  // fragment is lost; a state stays an order of magnitude below.
  EXPECT_LT(msg.getEncodedSize(), 8 * 1024);
}

TEST(SimProcessStateMessage, RoundTripsThroughEncodeAndBack) {
  RobotState state;
  state.time = 1.234567891;
  state.robot = "snake";
  Pose pose;
  pose.position = Eigen::Vector3d(0.1, -0.2, 0.3);
  pose.orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
  state.modules = {pose};
  state.frames = {pose, pose};
  JointState joint;
  joint.angle = 0.25;
  joint.speed = -1.5;
  joint.torque = 0.01;
  joint.world = pose;
  state.joints = {joint};
  SensorModuleState sensor;
  sensor.pose = pose;
  sensor.has_force = true;
  sensor.force = 2.5;
  sensor.distances = {0.4, 2.0};
  sensor.distance_faces = {4, 0};
  state.sensor_modules = {sensor};
  state.com = Eigen::Vector3d(1, 2, 3);
  state.com_velocity = Eigen::Vector3d(-1, 0, 0.5);
  state.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  state.heading = M_PI / 2;

  const robot_state_t msg = ToRobotStateMessage(state, 42);
  EXPECT_EQ(msg.seq, 42);
  EXPECT_EQ(msg.utime, 1234568);
  std::vector<uint8_t> bytes(msg.getEncodedSize());
  ASSERT_EQ(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  robot_state_t decoded;
  ASSERT_GE(decoded.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  const RobotState back = FromRobotStateMessage(decoded);
  EXPECT_EQ(back.time, state.time);
  EXPECT_EQ(back.robot, "snake");
  EXPECT_EQ(back.frames.size(), 2u);
  EXPECT_EQ(back.joints[0].world.position, pose.position);
  EXPECT_EQ(back.joints[0].world.orientation.coeffs(),
            pose.orientation.coeffs());
  EXPECT_EQ(back.joints[0].speed, -1.5);
  EXPECT_EQ(back.sensor_modules[0].distances, sensor.distances);
  EXPECT_EQ(back.sensor_modules[0].distance_faces, sensor.distance_faces);
  EXPECT_EQ(back.sensor_modules[0].force, 2.5);
  EXPECT_EQ(back.com, state.com);
  EXPECT_EQ(back.com_velocity, state.com_velocity);
  EXPECT_EQ(msg.orientation[0], state.orientation.w());  // w first on the wire
  EXPECT_EQ(msg.orientation[3], state.orientation.z());
  EXPECT_EQ(back.orientation.coeffs(), state.orientation.coeffs());
  EXPECT_EQ(back.heading, M_PI / 2);
}

joint_command_t Command(int64_t seq, int64_t state_seq,
                        std::vector<double> targets,
                        const std::string& sender = "ctl") {
  joint_command_t cmd{};
  cmd.seq = seq;
  cmd.robot = "snake";
  cmd.sender = sender;
  cmd.state_seq = state_seq;
  cmd.target = std::move(targets);
  cmd.num_joints = static_cast<int32_t>(cmd.target.size());
  return cmd;
}

TEST(SimProcessCommandFilter, ChecksRobotCountValuesAndSequence) {
  CommandFilter filter({"snake", "worm"}, {3, 5});
  const std::vector<std::string> none;
  const std::vector<double> ok = {0.1, -3.0, 3.14};
  EXPECT_EQ(filter.Check(Command(1, 0, ok), "snake", 0, false, none),
            CommandVerdict::kAccepted);
  EXPECT_EQ(filter.Check(Command(2, 0, {0.1, 0.2}), "snake", 0, false, none),
            CommandVerdict::kWrongJointCount);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(filter.Check(Command(3, 0, {0, nan, 0}), "snake", 0, false, none),
            CommandVerdict::kBadValue);
  EXPECT_EQ(filter.Check(Command(4, 0, {0, 0, 3.2}), "snake", 0, false, none),
            CommandVerdict::kBadValue);
  EXPECT_EQ(filter.Check(Command(5, 0, ok), "worm", 0, false, none),
            CommandVerdict::kUnknownRobot);  // channel says another robot
  // The accepted command again (a controller answering a re-sent state):
  // a repeat, not an error. Same numbers with other targets: stale.
  EXPECT_EQ(filter.Check(Command(1, 0, ok), "snake", 0, false, none),
            CommandVerdict::kRepeat);
  EXPECT_EQ(filter.Check(Command(1, 0, {0, 0, 0.5}), "snake", 0, false, none),
            CommandVerdict::kStaleSeq);
  EXPECT_EQ(filter.Check(Command(6, 2, ok), "snake", 2, false, none),
            CommandVerdict::kAccepted);
  // An answer to an older state than one applied.
  EXPECT_EQ(filter.Check(Command(7, 1, ok, "other"), "snake", 2, false, none),
            CommandVerdict::kStaleSeq);
  // A state that was never published.
  EXPECT_EQ(filter.Check(Command(8, 9, ok), "snake", 2, false, none),
            CommandVerdict::kStaleSeq);
  // "ctl" numbered 1..8; 2..4 were seen (and rejected), 5 went to the wrong
  // channel and 7 came from "other": two of its commands never arrived.
  EXPECT_EQ(filter.seq_gaps(), 2);
}

TEST(SimProcessCommandFilter, LockstepTakesOnlyNamedAnswersToTheCurrentState) {
  CommandFilter filter({"snake"}, {2});
  const std::vector<std::string> controllers = {"ctl"};
  EXPECT_EQ(filter.Check(Command(1, 4, {0, 0}, "rogue"), "snake", 4, true,
                         controllers),
            CommandVerdict::kNotController);
  EXPECT_EQ(filter.Check(Command(1, 3, {0, 0}), "snake", 4, true, controllers),
            CommandVerdict::kStaleSeq);
  EXPECT_EQ(filter.Check(Command(2, -1, {0, 0}), "snake", 4, true, controllers),
            CommandVerdict::kStaleSeq);
  EXPECT_EQ(filter.Check(Command(3, 4, {0, 0}), "snake", 4, true, controllers),
            CommandVerdict::kAccepted);
}

// --duration is the sim time to stop at: one the checkpoint is already
// past would end the run at once, in silence.
TEST(SimCommandLine, ADurationTheCheckpointIsPastIsRefused) {
  const std::string dir = testing::TempDir("sim_duration_checkpoint");
  Scenario scenario;
  scenario.robots.push_back(MakeChain(ChainOptions{}));
  Physics physics(scenario);
  physics.Step(500);
  const std::string checkpoint = dir + "/run.checkpoint";
  SaveCheckpoint(checkpoint, physics);
  const auto parse = [&](std::vector<std::string> args) {
    CLI::App app;
    SimCommandLine line;
    line.AddFlags(app);
    testing::ParseFlags(app, "mrsim-sim", args);
    line.Finish();
    return line.LoadPhysics();
  };
  const double t = physics.time();
  try {
    parse({"--load-checkpoint", checkpoint, "--duration", "0.5"});
    FAIL() << "ran nothing in silence";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "--duration 0.5 ends before the checkpoint's sim time"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NEAR(parse({"--load-checkpoint", checkpoint, "--duration",
                     std::to_string(t + 1)})
                  ->time(),
              t, 1e-12);
}

// mrsim-sim --load-checkpoint used to start without a word of what it
// loaded: the line names the file, its robots and the sim time.
TEST(SimCommandLine, TheLoadLineSaysWhatWasLoadedAndFromWhen) {
  const std::string dir = testing::TempDir("sim_load_line");
  Scenario scenario;
  ChainOptions chain;
  chain.name = "snake";
  chain.modules = 4;
  scenario.robots.push_back(MakeChain(chain));
  Physics physics(scenario);
  physics.Step(250);
  const std::string checkpoint = dir + "/run.checkpoint";
  SaveCheckpoint(checkpoint, physics);
  CLI::App app;
  SimCommandLine line;
  line.AddFlags(app);
  const std::vector<const char*> argv = {"mrsim-sim", "--load-checkpoint",
                                         checkpoint.c_str()};
  app.parse(static_cast<int>(argv.size()), argv.data());
  line.Finish();
  const auto loaded = line.LoadPhysics();
  EXPECT_EQ(line.LoadLine(*loaded),
            "mrsim-sim: loaded checkpoint " + checkpoint +
                ": 1 robot: snake (4 joints), continuing from sim time " +
                fmt::format("{:.3f}", physics.time()) + " s");
  SimCommandLine none;
  EXPECT_EQ(none.LoadLine(*loaded), "");
}

// The spinning send thread is the default; --no-spin is for a machine
// whose idle CPU time is not to be spent (docs/sim.md).
TEST(SimCommandLine, LockstepSpinsUnlessToldNot) {
  const auto spin = [](std::vector<std::string> args) {
    CLI::App app;
    SimCommandLine line;
    line.AddFlags(app);
    args.insert(args.begin(), {"mrsim-sim", "run.xml", "--clock", "lockstep",
                               "--controllers", "ctl"});
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    app.parse(static_cast<int>(argv.size()), argv.data());
    line.Finish();
    return line.options.spin;
  };
  EXPECT_TRUE(spin({}));
  EXPECT_FALSE(spin({"--no-spin"}));
}

// --controllers names whom lockstep waits for; under another clock it
// used to be accepted and the run went on in real time, unnoticed.
TEST(SimCommandLine, ControllersWithoutLockstepIsAUsageError) {
  for (const char* clock : {"realtime", "fast"}) {
    CLI::App app;
    SimCommandLine line;
    line.AddFlags(app);
    const std::vector<const char*> argv = {
        "mrsim-sim", "run.xml", "--clock", clock, "--controllers", "gait"};
    app.parse(static_cast<int>(argv.size()), argv.data());
    try {
      line.Finish();
      ADD_FAILURE() << clock << ": --controllers accepted";
    } catch (const UsageError& e) {
      EXPECT_NE(
          std::string(e.what()).find("--controllers needs --clock lockstep"),
          std::string::npos)
          << e.what();
    }
  }
  // Without --clock the file's saved clock decides; a file without one
  // runs realtime, so the same refusal comes when it is read.
  const std::string path =
      testing::TempDir("sim_controllers_realtime") + "/run.xml";
  Scenario scenario;
  scenario.robots.push_back(MakeChain(ChainOptions{}));
  WriteScenarioFile(scenario, path);
  CLI::App app;
  SimCommandLine line;
  line.AddFlags(app);
  const std::vector<const char*> argv = {"mrsim-sim", path.c_str(),
                                         "--controllers", "gait"};
  app.parse(static_cast<int>(argv.size()), argv.data());
  line.Finish();
  try {
    line.LoadPhysics();
    ADD_FAILURE() << "the default clock is realtime";
  } catch (const UsageError& e) {
    EXPECT_NE(
        std::string(e.what()).find("--controllers needs --clock lockstep"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mrsim
