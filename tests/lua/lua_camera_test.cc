// Cameras in Lua controllers: the grey thumbnail a script gets, and which
// picture mrsim-lua's node gives the script answering a state (in process,
// fake clock): in lockstep the same whatever order pictures, states and
// the camera's answers arrive in.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "camera/camera_image_codec.h"
#include "lcmtypes/runtime/channels.h"
#include "lua_controller/grey_thumbnail.h"
#include "lua_controller/process/lua_node.h"

namespace mrsim {
namespace {

TEST(GreyThumbnail, FitsIn32By24KeepingTheShapeAndAveragesBlocks) {
  // Left half black, right half white.
  std::vector<uint8_t> rgb(160 * 120 * 3, 0);
  for (int y = 0; y < 120; ++y) {
    for (int x = 80; x < 160; ++x) {
      std::fill_n(&rgb[(y * 160 + x) * 3], 3, 255);
    }
  }
  const GreyThumbnail t = MakeGreyThumbnail(160, 120, rgb.data());
  ASSERT_EQ(t.width, 32);
  ASSERT_EQ(t.height, 24);
  ASSERT_EQ(t.grey.size(), 32u * 24u);
  EXPECT_DOUBLE_EQ(t.grey[0], 0.0);
  EXPECT_NEAR(t.grey[31], 1.0, 1e-12);
  EXPECT_NEAR(t.grey[23 * 32 + 16], 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(t.grey[23 * 32 + 15], 0.0);

  const std::vector<uint8_t> red(640 * 120 * 3, 0);
  const GreyThumbnail wide = MakeGreyThumbnail(640, 120, red.data());
  EXPECT_EQ(wide.width, 32);
  EXPECT_EQ(wide.height, 6);
  const std::vector<uint8_t> small(20 * 10 * 3, 255);
  const GreyThumbnail same = MakeGreyThumbnail(20, 10, small.data());
  EXPECT_EQ(same.width, 20);  // never scaled up
  EXPECT_EQ(same.height, 10);
}

// Returns what it sees of camera 1 (state.cameras[1]): the picture's seq,
// its first grey value, the number of cameras and the picture's width.
const char* kCameraEcho =
    "function step(t, state)\n"
    "  local c = state.cameras[1]\n"
    "  if c == nil then return {-2, -2, #state.cameras, 0} end\n"
    "  return {c.seq, c.grey[1] or -1, #state.cameras, c.width}\n"
    "end\n";

robot_state_t State(int64_t seq) {
  robot_state_t s{};
  s.seq = seq;
  s.sim_time = 0.01 * static_cast<double>(seq);
  s.utime = seq * 10000;
  s.robot = "snake";
  s.num_joints = 4;
  s.joints.resize(4);
  return s;
}

// A 16x16 picture of state `seq` whose grey level tells the seq.
camera_image_t Picture(int64_t seq) {
  CameraImageHeader h;
  h.robot = "snake";
  h.sender = "mrsim-camera";
  h.seq = seq;
  h.sim_time = 0.01 * static_cast<double>(seq);
  CameraPicture p;
  p.width = 16;
  p.height = 16;
  p.rgb.assign(16 * 16 * 3, static_cast<uint8_t>(10 * seq));
  return EncodeCameraImage(h, p);
}

joint_command_t CameraAnswer(int64_t state_seq) {
  joint_command_t c{};
  c.robot = "snake";
  c.sender = "mrsim-camera";
  c.seq = state_seq;
  c.state_seq = state_seq;
  return c;
}

class LuaCameraTest : public ::testing::Test {
 protected:
  std::unique_ptr<LuaNode> Make(int cameras) {
    LuaNodeOptions o;
    o.robot = "snake";
    o.sender = "lua-snake";
    o.rate = 0;
    o.cameras = cameras;
    return std::make_unique<LuaNode>(
        o, std::make_unique<LuaScript>(kCameraEcho, "ctl.lua"),
        [](int n) { return std::vector<Axis>(n, Axis::kPitch); }, now_);
  }
  // The answers the node sent since the last call: state seq -> targets.
  std::vector<std::pair<int64_t, std::vector<double>>> Answers() {
    std::vector<std::pair<int64_t, std::vector<double>>> got;
    for (auto& [channel, msg] : out_.messages) {
      if (const auto* c = std::get_if<joint_command_t>(&msg)) {
        got.emplace_back(c->state_seq, c->target);
      }
    }
    out_.clear();
    return got;
  }
  WallTime now_{};
  LuaOutbox out_;
};

TEST_F(LuaCameraTest,
       LockstepWaitsForTheCamerasAnswerAndSeesThatStatesPicture) {
  auto node = Make(1);
  node->OnState(State(0), now_, &out_);
  EXPECT_TRUE(Answers().empty());  // the picture of state 0 may be on its way
  node->OnCameraImage(Picture(0), now_, &out_);
  EXPECT_TRUE(Answers().empty());  // a second camera's could be too
  node->OnCommand(CameraAnswer(0), now_, &out_);
  auto got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].first, 0);
  EXPECT_EQ(got[0].second[0], 0);  // seq of the picture seen
  EXPECT_EQ(got[0].second[2], 1);  // one camera
  EXPECT_EQ(got[0].second[3], 16);

  // No picture due at state 1: the camera answers, the script still sees
  // state 0's picture, whichever came first.
  node->OnCommand(CameraAnswer(1), now_, &out_);
  node->OnState(State(1), now_, &out_);
  got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].second[0], 0);

  // A picture of a later state that arrived early is not shown.
  node->OnState(State(2), now_, &out_);
  node->OnCameraImage(Picture(2), now_, &out_);
  node->OnCameraImage(Picture(3), now_, &out_);
  node->OnCommand(CameraAnswer(2), now_, &out_);
  got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].second[0], 2);
  EXPECT_NEAR(got[0].second[1], 20 / 255.0, 1e-12);
  EXPECT_EQ(node->counters().states_waited, 2);
  EXPECT_EQ(node->counters().camera_timeouts, 0);
}

TEST_F(LuaCameraTest, SameAnswersWhateverTheArrivalOrder) {
  std::vector<std::vector<double>> runs[2];
  for (int order = 0; order < 2; ++order) {
    auto node = Make(1);
    for (int64_t seq = 0; seq < 6; ++seq) {
      const bool due = seq % 2 == 0;  // a picture every other state
      if (order == 0) {
        node->OnState(State(seq), now_, &out_);
        if (due) node->OnCameraImage(Picture(seq), now_, &out_);
        node->OnCommand(CameraAnswer(seq), now_, &out_);
      } else {
        if (due) node->OnCameraImage(Picture(seq), now_, &out_);
        node->OnCommand(CameraAnswer(seq), now_, &out_);
        node->OnState(State(seq), now_, &out_);
      }
      for (auto& [s, targets] : Answers()) runs[order].push_back(targets);
    }
  }
  ASSERT_EQ(runs[0].size(), 6u);
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_EQ(runs[0][5][0], 4);  // state 5 sees state 4's picture
}

TEST_F(LuaCameraTest, MissingCameraProcessSlowsTheRunOnceThenIsNotWaitedFor) {
  auto node = Make(1);
  node->OnState(State(0), now_, &out_);
  node->Tick(now_, &out_);
  EXPECT_TRUE(Answers().empty());
  now_ = AfterSeconds(now_, LuaNode::kCameraWait + 0.1);
  node->Tick(now_, &out_);
  auto got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].second[0], -1);  // no picture yet
  EXPECT_EQ(got[0].second[2], 1);   // the scenario's camera, still listed
  EXPECT_EQ(node->counters().camera_timeouts, 1);
  node->OnState(State(1), now_, &out_);
  EXPECT_EQ(Answers().size(), 1u);  // at once
  const auto log = node->TakeLog();
  EXPECT_TRUE(std::any_of(log.begin(), log.end(), [](const std::string& l) {
    return l.find("no answer from mrsim-camera to state seq 0") !=
           std::string::npos;
  }));
  // Heard again: waited for again.
  node->OnCommand(CameraAnswer(1), now_, &out_);
  node->OnState(State(2), now_, &out_);
  EXPECT_TRUE(Answers().empty());
}

TEST_F(LuaCameraTest, HostilePicturesAreCountedAndDropped) {
  auto node = Make(1);
  camera_image_t bad = Picture(0);
  bad.width = 17;  // bytes for 16x16
  node->OnCameraImage(bad, now_, &out_);
  camera_image_t forged = Picture(0);
  forged.camera = 1 << 30;
  node->OnCameraImage(forged, now_, &out_);
  node->OnCommand(CameraAnswer(0), now_, &out_);
  node->OnState(State(0), now_, &out_);
  const auto got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].second[0], -1);
  EXPECT_EQ(got[0].second[2], 1);
  EXPECT_EQ(node->counters().pictures_malformed, 2);
  EXPECT_EQ(node->counters().pictures_received, 0);
}

TEST_F(LuaCameraTest, RobotWithoutCamerasReadsNoPictureAndNeverWaits) {
  auto node = Make(0);
  node->OnCameraImage(Picture(0), now_, &out_);
  node->OnState(State(0), now_, &out_);
  const auto got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].second[2], 0);  // #state.cameras
  EXPECT_EQ(node->counters().pictures_received, 0);
}

TEST_F(LuaCameraTest, UnknownCamerasAreTakenAsTheyComeUntilTheCameraIsHeard) {
  auto node = Make(-1);  // no --scenario
  node->OnState(State(0), now_, &out_);
  ASSERT_EQ(Answers().size(), 1u);  // nothing to wait for
  node->OnCameraImage(Picture(1), now_, &out_);
  node->OnState(State(1), now_, &out_);
  EXPECT_TRUE(Answers().empty());  // heard: waited for from now on
  node->OnCommand(CameraAnswer(1), now_, &out_);
  const auto got = Answers();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].second[0], 1);
}

}  // namespace
}  // namespace mrsim
