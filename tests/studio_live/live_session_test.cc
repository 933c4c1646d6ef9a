// The studio's LCM node core, in-process with a fake clock: what it hears,
// what it plots, what it sends and how answers are matched.
#include "studio/live/live_session.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <variant>
#include <vector>

#include "mrsim/joint_command_t.hpp"
#include "studio/live/plot_export.h"
#include "tests/common/child_process.h"
#include "tests/logger/test_messages.h"

namespace mrsim::studio {
namespace {

template <typename T>
std::vector<uint8_t> Bytes(const T& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

class LiveSessionTest : public ::testing::Test {
 protected:
  LiveSessionTest() : session_(Options()) {}
  static LiveSessionOptions Options() {
    LiveSessionOptions o;
    o.prefix = "TEST";
    o.sender = "studio-1";
    return o;
  }
  template <typename T>
  void Hear(const std::string& channel, const T& msg) {
    const auto b = Bytes(msg);
    session_.OnMessage(channel, b.data(), b.size(), now_);
  }
  void Advance(double s) {
    now_ += std::chrono::duration_cast<WallClock::duration>(
        std::chrono::duration<double>(s));
    session_.Tick(now_);
  }
  sim_status_t Status(const std::string& sender, int64_t seq, bool ok) {
    sim_status_t s{};
    s.control_sender = sender;
    s.control_seq = seq;
    s.control_ok = ok;
    s.clock = "realtime";
    s.last_error = ok ? "" : "not paused";
    return s;
  }

  WallTime now_{};
  LiveSession session_;
  StudioOutbox out_;
};

TEST_F(LiveSessionTest, ListsTheRobotsItHearsAndMarksSilentOnes) {
  Hear("TEST_STATE_snake", testing::KnownRobotState(0, 4, 1, "snake"));
  Hear("TEST_STATE_worm", testing::KnownRobotState(0, 3, 0, "worm"));
  // Another simulation's prefix is not ours.
  Hear("OTHER_STATE_eel", testing::KnownRobotState(0, 3, 0, "eel"));
  const auto robots = session_.robots();
  ASSERT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots[0]->name, "snake");
  EXPECT_EQ(robots[1]->name, "worm");
  EXPECT_EQ(robots[0]->state.num_modules, 4);
  EXPECT_EQ(session_.malformed() + session_.foreign(), 0);

  Advance(1.0);
  Hear("TEST_STATE_snake", testing::KnownRobotState(1, 4, 1, "snake"));
  Advance(1.5);  // worm last heard 2.5 s ago, snake 1.5 s ago
  EXPECT_FALSE(session_.robot("snake")->silent);
  EXPECT_TRUE(session_.robot("worm")->silent);
  EXPECT_EQ(session_.robot("snake")->states, 2);
  EXPECT_EQ(session_.robot("snake")->state.seq, 1);
}

// The loose parts' state (<prefix>_STATE_loose) is no robot to list or
// steer: it is kept apart, newest first.
TEST_F(LiveSessionTest, LoosePartsStateIsKeptApartFromTheRobots) {
  Hear("TEST_STATE_snake", testing::KnownRobotState(0, 4, 1, "snake"));
  Hear("TEST_STATE_loose", testing::KnownRobotState(0, 0, 2, "loose"));
  Hear("TEST_STATE_loose", testing::KnownRobotState(1, 0, 2, "loose"));
  const auto robots = session_.robots();
  ASSERT_EQ(robots.size(), 1u);
  EXPECT_EQ(robots[0]->name, "snake");
  ASSERT_TRUE(session_.loose().has_value());
  EXPECT_EQ(session_.loose()->seq, 1);
  EXPECT_EQ(session_.loose()->num_sensor_modules, 2);
  EXPECT_EQ(session_.malformed() + session_.foreign(), 0);
}

TEST_F(LiveSessionTest, PlotBufferHoldsExactlyTheValuesTheStatesCarried) {
  PlotSeries& force =
      session_.AddPlot("TEST_STATE_snake", "sensor_module0.force", 0.02);
  PlotSeries& angle =
      session_.AddPlot("TEST_STATE_snake", "module2.joint.angle", 100);
  std::vector<double> sent_force, sent_angle, sent_time;
  for (int64_t seq = 0; seq < 50; ++seq) {
    const robot_state_t s = testing::KnownRobotState(seq, 4, 1, "snake");
    sent_force.push_back(s.sensor_modules[0].force);
    sent_angle.push_back(s.joints[2].angle);
    sent_time.push_back(static_cast<double>(s.utime) / 1e6);
    Hear("TEST_STATE_snake", s);
  }
  // All 50 angles (the window holds them), bit for bit.
  ASSERT_EQ(angle.values().size(), 50u);
  for (size_t i = 0; i < 50; ++i) {
    EXPECT_EQ(angle.values()[i], sent_angle[i]) << i;
    EXPECT_EQ(angle.times()[i], sent_time[i]) << i;
  }
  // A 20 ms window at 1 kHz keeps the newest 21 forces.
  EXPECT_EQ(force.received(), 50);
  ASSERT_EQ(force.values().size(), 21u);
  for (size_t i = 0; i < 21; ++i) {
    EXPECT_EQ(force.values()[i], sent_force[29 + i]) << i;
  }
  // Plot columns are mrsim-log's CSV columns.
  const auto cols = session_.Columns("TEST_STATE_snake");
  EXPECT_NE(std::find(cols.begin(), cols.end(), "sensor_module0.force"),
            cols.end());
  EXPECT_NE(std::find(cols.begin(), cols.end(), "com.x"), cols.end());
  EXPECT_EQ(std::find(cols.begin(), cols.end(), "robot"), cols.end());
  EXPECT_EQ(std::find(cols.begin(), cols.end(), "seq"), cols.end());
}

TEST_F(LiveSessionTest, ImuReadingsArePlottedLiveByTheirLogColumns) {
  // The IMU's six values travel as a reading; the plot names them as the
  // logger's CSV does and holds what the states carried.
  PlotSeries& accel_z =
      session_.AddPlot("TEST_STATE_snake", "sensor_module0.imu.accel.z", 100);
  PlotSeries& gyro_x =
      session_.AddPlot("TEST_STATE_snake", "sensor_module0.imu.gyro.x", 100);
  std::vector<double> sent_accel_z, sent_gyro_x;
  for (int64_t seq = 0; seq < 10; ++seq) {
    robot_state_t s = testing::KnownRobotState(seq, 4, 1, "snake");
    sensor_reading_t imu{};
    imu.kind = "imu";
    imu.face = -1;
    imu.values = {0.1, -0.2, 9.81 + 0.01 * seq, 0.5 * seq, 0.0, -0.3};
    imu.num_values = static_cast<int32_t>(imu.values.size());
    s.sensor_modules[0].readings = {imu};
    s.sensor_modules[0].num_readings = 1;
    sent_accel_z.push_back(imu.values[2]);
    sent_gyro_x.push_back(imu.values[3]);
    Hear("TEST_STATE_snake", s);
  }
  const auto cols = session_.Columns("TEST_STATE_snake");
  for (const char* c :
       {"sensor_module0.imu.accel.x", "sensor_module0.imu.accel.z",
        "sensor_module0.imu.gyro.x", "sensor_module0.imu.gyro.z"}) {
    EXPECT_NE(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  }
  ASSERT_EQ(accel_z.values().size(), 10u);
  ASSERT_EQ(gyro_x.values().size(), 10u);
  for (size_t i = 0; i < 10; ++i) {
    EXPECT_EQ(accel_z.values()[i], sent_accel_z[i]) << i;
    EXPECT_EQ(gyro_x.values()[i], sent_gyro_x[i]) << i;
  }
}

TEST_F(LiveSessionTest, PausedPlotTakesNothingAndAResetStartsItAfresh) {
  PlotSeries& p = session_.AddPlot("TEST_STATE_snake", "com.x", 10);
  Hear("TEST_STATE_snake", testing::KnownRobotState(5, 2, 0, "snake"));
  p.set_paused(true);
  Hear("TEST_STATE_snake", testing::KnownRobotState(6, 2, 0, "snake"));
  EXPECT_EQ(p.values().size(), 1u);
  p.set_paused(false);
  // Time going back (RESET, a loaded checkpoint) clears the old curve.
  Hear("TEST_STATE_snake", testing::KnownRobotState(0, 2, 0, "snake"));
  ASSERT_EQ(p.values().size(), 1u);
  EXPECT_EQ(p.times()[0], 17e-6);
}

// A stalled pipelined lockstep sim re-sends the two states it awaits, older
// first: the curve keeps its history and gets no second point.
TEST_F(LiveSessionTest, PlotIgnoresResentStatesAndStillClearsOnAReset) {
  PlotSeries& p = session_.AddPlot("TEST_STATE_snake", "com.x", 10);
  for (int64_t seq : {0, 1, 2, 3, 2, 3, 2, 3, 4}) {
    Hear("TEST_STATE_snake", testing::KnownRobotState(seq, 2, 0, "snake"));
  }
  ASSERT_EQ(p.values().size(), 5u);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(
        p.times()[i],
        testing::KnownRobotState(static_cast<int64_t>(i), 2, 0).utime / 1e6);
  }
  // A new run back at the time of state 2, moving differently.
  robot_state_t other = testing::KnownRobotState(2, 2, 0, "snake");
  other.com[0] += 0.25;
  Hear("TEST_STATE_snake", other);
  ASSERT_EQ(p.values().size(), 1u);
  EXPECT_EQ(p.values()[0], other.com[0]);
}

TEST_F(LiveSessionTest, SimRequestsAreAnsweredOnlyByTheirOwnSenderAndSeq) {
  const int64_t pause = session_.Pause(now_, &out_);
  const int64_t step = session_.Step(10, now_, &out_);
  ASSERT_EQ(out_.messages.size(), 2u);
  EXPECT_EQ(out_.messages[0].first, "TEST_SIM_CONTROL");
  const auto& p = std::get<sim_control_t>(out_.messages[0].second);
  EXPECT_EQ(p.command, +sim_control_t::PAUSE);
  EXPECT_EQ(p.sender, "studio-1");
  EXPECT_EQ(p.seq, pause);
  const auto& s = std::get<sim_control_t>(out_.messages[1].second);
  EXPECT_EQ(s.command, +sim_control_t::STEP);
  EXPECT_EQ(s.steps, 10);
  EXPECT_EQ(s.seq, step);
  EXPECT_NE(pause, step);

  // mrsim-ctl's answer with the same seq is not ours.
  Hear("TEST_SIM_STATUS", Status("mrsim-ctl-7", pause, true));
  EXPECT_EQ(session_.request(pause)->state, LiveRequest::State::kPending);
  Hear("TEST_SIM_STATUS", Status("studio-1", pause, true));
  EXPECT_EQ(session_.request(pause)->state, LiveRequest::State::kDone);
  Hear("TEST_SIM_STATUS", Status("studio-1", step, false));
  EXPECT_EQ(session_.request(step)->state, LiveRequest::State::kRefused);
  EXPECT_EQ(session_.request(step)->error, "not paused");
  ASSERT_TRUE(session_.sim_status().has_value());
  EXPECT_EQ(session_.sim_status()->clock, "realtime");

  // Nobody answers a reset: after the timeout it says so.
  const int64_t reset = session_.Reset(now_, &out_);
  Advance(2.9);
  EXPECT_EQ(session_.request(reset)->state, LiveRequest::State::kPending);
  Advance(0.2);
  EXPECT_EQ(session_.request(reset)->state, LiveRequest::State::kNoAnswer);
  EXPECT_EQ(session_.request(reset)->error, "no answer within 3 s");
}

TEST_F(LiveSessionTest, BadRequestsAreRefusedBeforeAnythingIsSent) {
  EXPECT_THROW(session_.Step(0, now_, &out_), std::invalid_argument);
  EXPECT_THROW(session_.SetSpeed(0, now_, &out_), std::invalid_argument);
  EXPECT_THROW(session_.SaveCheckpoint("", now_, &out_), std::invalid_argument);
  EXPECT_THROW(session_.Steer("snake", "fowrard", 1, now_, &out_),
               std::invalid_argument);
  EXPECT_THROW(session_.Steer("snake", "forward", 1.5, now_, &out_),
               std::invalid_argument);
  EXPECT_THROW(session_.Steer("", "forward", 1, now_, &out_),
               std::invalid_argument);
  EXPECT_THROW(session_.SetGaitParameters("snake", {1, 2, 3}, now_, &out_),
               std::invalid_argument);
  EXPECT_TRUE(out_.empty());
  EXPECT_TRUE(session_.requests().empty());
}

TEST_F(LiveSessionTest, SteeringGoesToTheRobotsGaitNodeAndItsStatusAnswers) {
  const int64_t seq = session_.Steer("snake", "turn_left", 0.5, now_, &out_);
  ASSERT_EQ(out_.messages.size(), 1u);
  EXPECT_EQ(out_.messages[0].first, "TEST_GAIT_snake");
  const auto& g = std::get<gait_command_t>(out_.messages[0].second);
  EXPECT_EQ(g.motion, "turn-left");
  EXPECT_EQ(g.strength, 0.5);
  EXPECT_EQ(g.robot, "snake");
  EXPECT_EQ(g.sender, "studio-1");
  EXPECT_FALSE(g.has_parameters);

  const int64_t params = session_.SetGaitParameters(
      "snake", {0.5, 0, 2.5, 0, 4, 0, 0}, now_, &out_);
  const auto& pg = std::get<gait_command_t>(out_.messages[1].second);
  EXPECT_TRUE(pg.has_parameters);
  EXPECT_EQ(pg.parameters[4], 4.0);

  gait_status_t st{};
  st.robot = "snake";
  st.gait = "turn";
  st.motion = "turn-left";
  st.command_sender = "studio-1";
  st.command_seq = seq;
  st.command_result = gait_status_t::APPLIED;
  Hear("TEST_GAIT_STATUS_snake", st);
  EXPECT_EQ(session_.request(seq)->state, LiveRequest::State::kDone);
  st.command_seq = params;
  st.command_result = gait_status_t::REJECTED;
  st.command_error = "period must be positive";
  Hear("TEST_GAIT_STATUS_snake", st);
  EXPECT_EQ(session_.request(params)->state, LiveRequest::State::kRefused);
  EXPECT_EQ(session_.request(params)->error, "period must be positive");
  ASSERT_NE(session_.robot("snake"), nullptr);
  ASSERT_TRUE(session_.robot("snake")->gait.has_value());
  EXPECT_EQ(session_.robot("snake")->gait->motion, "turn-left");
}

// A gait controller says it takes steering by its gait status; a robot
// whose controller never says so (mrsim-lua) is not steered into "no
// answer within 3 s": the request is refused at once, with why.
TEST_F(LiveSessionTest, SteeringIsRefusedAtOnceForARobotNothingSteers) {
  using State = Steering::State;
  gait_status_t heartbeat{};
  heartbeat.robot = "snake";
  heartbeat.running = true;
  EXPECT_EQ(session_.SteeringOf("snake", now_).state, State::kUnknown);
  for (int i = 0; i < 3; ++i) {
    Hear("TEST_STATE_snake", testing::KnownRobotState(i, 4, 1, "snake"));
    Hear("TEST_STATE_worm", testing::KnownRobotState(i, 3, 0, "worm"));
    if (i == 0) {
      // Too early to tell: a gait controller may not have spoken yet.
      EXPECT_EQ(session_.SteeringOf("worm", now_).state, State::kUnknown);
    }
    Hear("TEST_GAIT_STATUS_snake", heartbeat);
    Advance(1.0);
  }
  EXPECT_EQ(session_.SteeringOf("snake", now_).state, State::kAnswered);
  const Steering worm = session_.SteeringOf("worm", now_);
  EXPECT_EQ(worm.state, State::kUnanswered);
  EXPECT_NE(worm.why.find("robot 'worm' cannot be steered"), std::string::npos)
      << worm.why;

  EXPECT_THROW(session_.Steer("worm", "forward", 1, now_, &out_),
               std::runtime_error);
  EXPECT_THROW(session_.SetGait("worm", "turn", now_, &out_),
               std::runtime_error);
  EXPECT_TRUE(out_.empty());
  EXPECT_TRUE(session_.requests().empty());
  session_.Steer("snake", "forward", 1, now_, &out_);
  ASSERT_EQ(out_.messages.size(), 1u);
  EXPECT_EQ(out_.messages[0].first, "TEST_GAIT_snake");

  // The gait controller stopped: steering it is refused too, and says so.
  Advance(3.8);
  const Steering gone = session_.SteeringOf("snake", now_);
  EXPECT_EQ(gone.state, State::kUnanswered);
  EXPECT_NE(gone.why.find("has not been heard for 5 s"), std::string::npos)
      << gone.why;
}

TEST_F(LiveSessionTest, MalformedAndForeignMessagesAreCountedAndDropped) {
  const auto good = Bytes(testing::KnownRobotState(0, 3, 1, "snake"));
  // Cut short, one byte too many, random bytes, empty.
  auto cut = good;
  cut.resize(cut.size() / 2);
  session_.OnMessage("TEST_STATE_snake", cut.data(), cut.size(), now_);
  auto longer = good;
  longer.push_back(0);
  session_.OnMessage("TEST_STATE_snake", longer.data(), longer.size(), now_);
  auto forged = good;  // fingerprint kept, num_modules made huge
  forged[8 + 8 + 8 + 4 + 6 + 8] = 0x7f;  // after utime, seq, robot, sim_time
  session_.OnMessage("TEST_STATE_snake", forged.data(), forged.size(), now_);
  session_.OnMessage("TEST_STATE_snake", nullptr, 0, now_);
  EXPECT_EQ(session_.malformed(), 4);

  // A known type on a channel that carries another; an unknown type; a
  // state of another robot on this robot's channel.
  joint_command_t cmd{};
  cmd.robot = "snake";
  Hear("TEST_STATE_snake", cmd);
  std::vector<uint8_t> unknown(64, 0xab);
  session_.OnMessage("TEST_SIM_STATUS", unknown.data(), unknown.size(), now_);
  Hear("TEST_STATE_snake", testing::KnownRobotState(0, 3, 1, "eel"));
  EXPECT_EQ(session_.foreign(), 3);
  EXPECT_TRUE(session_.robots().empty());
  EXPECT_FALSE(session_.last_error().empty());

  // And the good one still gets through afterwards.
  session_.OnMessage("TEST_STATE_snake", good.data(), good.size(), now_);
  EXPECT_EQ(session_.robots().size(), 1u);
}

TEST_F(LiveSessionTest, APlotExportsAsAPngWithEveryPointItHolds) {
  PlotSeries& p =
      session_.AddPlot("TEST_STATE_snake", "sensor_module0.force", 100);
  const std::string png = testing::TempDir("live_plot_export") + "/force.png";
  EXPECT_THROW(ExportPlotPng(p, png), PlotInputError);  // nothing yet
  for (int64_t seq = 0; seq < 30; ++seq) {
    Hear("TEST_STATE_snake", testing::KnownRobotState(seq, 2, 1, "snake"));
  }
  const PlotResult r = ExportPlotPng(p, png);
  EXPECT_EQ(r.points, 30u);
  EXPECT_TRUE(r.lines);
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
}

}  // namespace
}  // namespace mrsim::studio
