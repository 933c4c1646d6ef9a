// CameraNode in process with a fake clock and a fake (or the real)
// renderer: which states are pictured (frame k at sim time k / rate), the
// lockstep answers (after the picture, for every state, again for a
// re-sent one), drops in realtime, and hostile states and pictures counted
// and dropped. No sockets, no sleeps.
#include "camera/camera_node.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"
#include "camera/state_camera_renderer.h"
#include "sim_core/codec/state_message.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/chain_builder.h"

namespace mrsim {
namespace {

// Robots "a" (one camera at `rate`) and "b" (none); pictures of 16x16
// whose bytes are the seq.
class FakeRenderer : public CameraFrameRenderer {
 public:
  // `scene_camera`: a fixed camera on scene object 0 as well.
  explicit FakeRenderer(double rate = 30, bool scene_camera = false) {
    ScenarioCamera c;
    c.robot = 0;
    c.owner = "a";
    c.sensor_module = 0;
    c.name = "a/sm0/camera";
    c.part.width = 16;
    c.part.height = 16;
    c.part.rate = rate;
    cameras_.push_back(c);
    if (scene_camera) {
      c.robot = -1;
      c.owner = "scene";
      c.sensor_module = -1;
      c.scene_object = 0;
      c.name = "scene/obj0/camera";
      cameras_.push_back(c);
    }
  }
  const std::vector<std::string>& robots() const override { return robots_; }
  const std::vector<ScenarioCamera>& cameras() const override {
    return cameras_;
  }
  std::string Check(int, const RobotState& state) const override {
    return state.joints.size() == 2 ? "" : "expected 2 joints";
  }
  std::string CheckScene(const std::vector<SceneObjectState>&) const override {
    return "";
  }
  bool has_loose_parts() const override { return loose_parts; }
  std::string CheckLoose(const RobotState& loose) const override {
    return loose.sensor_modules.size() == 1 ? "" : "expected 1 sensor module";
  }
  void Render(int camera, const std::vector<const RobotState*>& states,
              const std::vector<SceneObjectState>*, const RobotState* loose,
              std::int64_t seq, CameraPicture* picture) override {
    ++renders;
    loose_time = loose != nullptr ? loose->time : -1;
    posed_with = 0;
    for (const RobotState* s : states) posed_with += s != nullptr;
    picture->width = cameras_[camera].part.width;
    picture->height = cameras_[camera].part.height;
    picture->rgb.assign(16 * 16 * 3, static_cast<std::uint8_t>(seq));
  }

  int renders = 0;
  int posed_with = 0;
  bool loose_parts = false;
  double loose_time = -1;  // of the loose state of the last Render; -1 none

 private:
  std::vector<std::string> robots_ = {"a", "b"};
  std::vector<ScenarioCamera> cameras_;
};

robot_state_t State(const std::string& robot, std::int64_t seq,
                    double sim_time) {
  robot_state_t s{};
  s.robot = robot;
  s.seq = seq;
  s.sim_time = sim_time;
  // (A forged time gets utime 0: the node judges sim_time.)
  s.utime = std::isfinite(sim_time) && std::abs(sim_time) < 1e9
                ? SimTimeToUtime(sim_time)
                : 0;
  s.joints.resize(2);
  s.num_joints = 2;
  s.orientation[0] = 1;
  return s;
}

CameraNodeOptions Options(ClockMode clock) {
  CameraNodeOptions o;
  o.clock = clock;
  return o;
}

// Both robots' states of period `seq` at `seq` x 10 ms.
void Period(CameraNode& node, std::int64_t seq, CameraOutbox* out,
            WallTime now = {}) {
  const double t = static_cast<double>(seq) * 0.01;
  node.OnState("MRSIM_STATE_a", State("a", seq, t), now, out);
  node.OnState("MRSIM_STATE_b", State("b", seq, t), now, out);
}

std::vector<std::int64_t> PicturedSeqs(const CameraOutbox& out) {
  std::vector<std::int64_t> seqs;
  for (const auto& [channel, msg] : out.messages) {
    if (const auto* image = std::get_if<camera_image_t>(&msg)) {
      EXPECT_EQ(channel, "MRSIM_CAMERA_a");
      seqs.push_back(image->seq);
    }
  }
  return seqs;
}

TEST(CameraNode, FrameKIsTheFirstStateAtOrAfterKOverTheRate) {
  FakeRenderer renderer(30);
  CameraNode node(Options(ClockMode::kLockstep), &renderer, WallTime{});
  CameraOutbox out;
  for (std::int64_t seq = 0; seq <= 100; ++seq) Period(node, seq, &out);
  // 100 Hz states, 30 Hz frames: frame k at k/30 s is the state at the
  // next 10 ms at or after it, and every one of the 31 frames comes.
  const std::vector<std::int64_t> seqs = PicturedSeqs(out);
  ASSERT_EQ(seqs.size(), 31u);
  EXPECT_EQ(seqs[0], 0);
  EXPECT_EQ(seqs[1], 4);   // 1/30 = 0.0333
  EXPECT_EQ(seqs[2], 7);   // 0.0667
  EXPECT_EQ(seqs[3], 10);  // 0.1 exactly
  EXPECT_EQ(seqs[30], 100);
  EXPECT_EQ(node.counters().pictures, 31);
  EXPECT_EQ(node.counters().dropped, 0);
  // Posed from both robots' states of the same period.
  EXPECT_EQ(renderer.posed_with, 2);
}

TEST(CameraNode, LockstepAnswersEveryStateAfterItsPicture) {
  FakeRenderer renderer(30);
  CameraNodeOptions o = Options(ClockMode::kLockstep);
  o.sender = "eye";
  CameraNode node(o, &renderer, WallTime{});
  CameraOutbox out;
  // Robot a's state alone is not a period: nothing yet.
  node.OnState("MRSIM_STATE_a", State("a", 0, 0.0), WallTime{}, &out);
  EXPECT_TRUE(out.empty());
  node.OnState("MRSIM_STATE_b", State("b", 0, 0.0), WallTime{}, &out);
  ASSERT_EQ(out.messages.size(), 2u);
  const auto* image = std::get_if<camera_image_t>(&out.messages[0].second);
  ASSERT_NE(image, nullptr);  // the picture first ...
  EXPECT_EQ(image->sender, "eye");
  EXPECT_EQ(DecodeCameraImage(*image).rgb,
            std::vector<std::uint8_t>(16 * 16 * 3, 0));
  const auto* answer = std::get_if<joint_command_t>(&out.messages[1].second);
  ASSERT_NE(answer, nullptr);  // ... then the answer, for robot a only
  EXPECT_EQ(out.messages[1].first, "MRSIM_COMMAND_a");
  EXPECT_EQ(answer->robot, "a");
  EXPECT_EQ(answer->sender, "eye");
  EXPECT_EQ(answer->state_seq, 0);
  EXPECT_EQ(answer->num_joints, 0);
  EXPECT_TRUE(answer->target.empty());
  out.clear();
  // A state between frames is answered without a picture.
  Period(node, 1, &out);
  ASSERT_EQ(out.messages.size(), 1u);
  answer = std::get_if<joint_command_t>(&out.messages[0].second);
  ASSERT_NE(answer, nullptr);
  EXPECT_EQ(answer->state_seq, 1);
  const joint_command_t first = *answer;
  out.clear();
  // The simulator sends the state again (our answer was lost): the same
  // answer again, no second picture.
  node.OnState("MRSIM_STATE_a", State("a", 1, 0.01), WallTime{}, &out);
  node.OnState("MRSIM_STATE_b", State("b", 1, 0.01), WallTime{}, &out);
  ASSERT_EQ(out.messages.size(), 1u);
  answer = std::get_if<joint_command_t>(&out.messages[0].second);
  ASSERT_NE(answer, nullptr);
  EXPECT_EQ(answer->seq, first.seq);
  EXPECT_EQ(answer->state_seq, 1);
  EXPECT_EQ(renderer.renders, 1);
}

// A camera on a scene object (on no robot) publishes on
// <prefix>_CAMERA_scene; it shows every robot, so in lockstep every robot
// is answered, whichever robot's controller waits for its pictures.
TEST(CameraNode, ASceneCameraPublishesOnTheSceneChannelAndAnswersEveryRobot) {
  FakeRenderer renderer(30, /*scene_camera=*/true);
  for (const std::string only : {"", "scene"}) {
    SCOPED_TRACE("--robot '" + only + "'");
    CameraNodeOptions o = Options(ClockMode::kLockstep);
    o.robot = only;
    CameraNode node(o, &renderer, WallTime{});
    CameraOutbox out;
    Period(node, 0, &out);
    std::vector<std::string> pictures, answers;
    for (const auto& [channel, msg] : out.messages) {
      if (const auto* image = std::get_if<camera_image_t>(&msg)) {
        pictures.push_back(
            channel + " " + image->robot + " " + std::to_string(image->camera) +
            " " + std::to_string(image->sensor_module) + " " + image->name);
      } else {
        answers.push_back(channel);
      }
    }
    std::vector<std::string> expected = {
        "MRSIM_CAMERA_scene scene 0 -1 scene/obj0/camera"};
    if (only.empty()) {
      expected.insert(expected.begin(), "MRSIM_CAMERA_a a 0 0 a/sm0/camera");
    }
    EXPECT_EQ(pictures, expected);
    EXPECT_EQ(answers,
              (std::vector<std::string>{"MRSIM_COMMAND_a", "MRSIM_COMMAND_b"}));
  }
}

TEST(CameraNode, RealtimePicturesTheNewestStateCountsDropsAndNeverAnswers) {
  FakeRenderer renderer(30);
  CameraNode node(Options(ClockMode::kRealtime), &renderer, WallTime{});
  CameraOutbox out;
  Period(node, 0, &out);
  EXPECT_TRUE(out.empty());  // nothing until the adapter flushes
  node.Flush(&out);
  EXPECT_EQ(PicturedSeqs(out), std::vector<std::int64_t>{0});
  out.clear();
  // Ten periods arrive while a picture was being taken: only the newest is
  // pictured; frames 1 and 2 (at 0.033 and 0.067 s) were passed over.
  for (std::int64_t seq = 1; seq <= 10; ++seq) Period(node, seq, &out);
  node.Flush(&out);
  EXPECT_EQ(PicturedSeqs(out), std::vector<std::int64_t>{10});
  EXPECT_EQ(node.counters().dropped, 2);
  for (const auto& entry : out.messages) {
    EXPECT_EQ(std::get_if<joint_command_t>(&entry.second), nullptr);
  }
  // A state older than one taken is stale, not a picture.
  out.clear();
  Period(node, 9, &out);
  node.Flush(&out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(node.counters().stale, 2);
  EXPECT_NE(node.Summary().find("pictures published 2, dropped 2, malformed 0"),
            std::string::npos)
      << node.Summary();
}

// A camera started after the simulator: the frames it never heard of are
// not drops.
TEST(CameraNode, FramesStartAtTheFirstStateHeard) {
  FakeRenderer renderer(30);
  CameraNode node(Options(ClockMode::kRealtime), &renderer, WallTime{});
  CameraOutbox out;
  Period(node, 50, &out);
  node.Flush(&out);
  Period(node, 54, &out);
  node.Flush(&out);
  EXPECT_EQ(PicturedSeqs(out), (std::vector<std::int64_t>{50, 54}));
  EXPECT_EQ(node.counters().dropped, 0);
}

TEST(CameraNode, ATimeGoingBackStartsTheFramesOverThere) {
  FakeRenderer renderer(10);
  CameraNode node(Options(ClockMode::kLockstep), &renderer, WallTime{});
  CameraOutbox out;
  for (std::int64_t seq = 0; seq <= 30; ++seq) Period(node, seq, &out);
  out.clear();
  // A reset: seq goes on, the time starts at 0 again.
  node.OnState("MRSIM_STATE_a", State("a", 31, 0.0), WallTime{}, &out);
  node.OnState("MRSIM_STATE_b", State("b", 31, 0.0), WallTime{}, &out);
  EXPECT_EQ(PicturedSeqs(out), std::vector<std::int64_t>{31});
}

TEST(CameraNode, ForeignAndMalformedStatesAreCountedAndDropped) {
  FakeRenderer renderer(30);
  CameraNode node(Options(ClockMode::kLockstep), &renderer, WallTime{});
  CameraOutbox out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  node.OnState("MRSIM_STATE_c", State("c", 0, 0), WallTime{}, &out);
  node.OnState("MRSIM_STATE_a", State("b", 0, 0), WallTime{}, &out);
  node.OnState("MRSIM_STATE_a", State("a", -1, 0), WallTime{}, &out);
  node.OnState("MRSIM_STATE_a", State("a", 0, nan), WallTime{}, &out);
  node.OnState("MRSIM_STATE_a", State("a", 0, 1e300), WallTime{}, &out);
  robot_state_t three = State("a", 0, 0);
  three.joints.resize(3);
  three.num_joints = 3;
  node.OnState("MRSIM_STATE_a", three, WallTime{}, &out);
  node.OnMalformed("MRSIM_STATE_a: cannot decode robot_state_t");
  scene_state_t scene{};
  scene.seq = -5;
  node.OnScene(scene, WallTime{});
  EXPECT_EQ(node.counters().malformed, 8);
  EXPECT_EQ(node.counters().states, 0);
  EXPECT_TRUE(out.empty());
  // Nothing was trusted: the good period after them is pictured.
  Period(node, 0, &out);
  EXPECT_EQ(PicturedSeqs(out), std::vector<std::int64_t>{0});
  EXPECT_NE(node.Summary().find("malformed 8"), std::string::npos);
}

TEST(CameraNode, RefusesWhatWouldWaitForNothing) {
  FakeRenderer renderer;
  CameraNodeOptions o = Options(ClockMode::kLockstep);
  o.robot = "b";  // has no camera
  EXPECT_THROW(CameraNode node(o, &renderer, WallTime{}),
               std::invalid_argument);
  o.robot = "ghost";
  EXPECT_THROW(CameraNode node(o, &renderer, WallTime{}),
               std::invalid_argument);
  o.robot = "a";
  o.jpeg_quality = 101;
  EXPECT_THROW(CameraNode node(o, &renderer, WallTime{}),
               std::invalid_argument);
}

// A snake with a head camera and a red ball ahead, rendered for real.
Scenario SnakeWithCamera() {
  ChainScenarioOptions options;
  options.chain.name = "eye";
  options.chain.modules = 3;
  options.chain.pattern = ChainPattern::kYaw;
  options.chain.sensor_after = {-1};
  Scenario s = MakeChainScenario(options);
  Camera camera;
  camera.width = 48;
  camera.height = 32;
  camera.noise = 4;
  camera.seed = 3;
  s.robots[0].sensor_modules[0].cameras.push_back(camera);
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d::Constant(0.1);
  ball.position =
      s.robots[0].sensor_modules[0].position + Eigen::Vector3d(0.4, 0, 0);
  ball.position.z() = 0.05;
  ball.is_static = true;
  ball.material_name = "red";
  s.scene_objects.push_back(ball);
  return s;
}

TEST(CameraNode, TheSameStateGivesTheSamePictureBitForBitRgbAndJpeg) {
  const Scenario s = SnakeWithCamera();
  Physics physics(s);
  const robot_state_t state = ToRobotStateMessage(physics.ReadRobotState(0), 7);
  std::vector<camera_image_t> images;
  for (int run = 0; run < 2; ++run) {
    for (int quality : {0, 80}) {
      StateCameraRenderer renderer(s);
      CameraNodeOptions o = Options(ClockMode::kLockstep);
      o.jpeg_quality = quality;
      CameraNode node(o, &renderer, WallTime{});
      CameraOutbox out;
      node.OnState("MRSIM_STATE_eye", state, WallTime{}, &out);
      ASSERT_EQ(out.messages.size(), 2u);  // the picture, the answer
      images.push_back(std::get<camera_image_t>(out.messages[0].second));
    }
  }
  ASSERT_EQ(images.size(), 4u);
  EXPECT_EQ(images[0].encoding, "rgb8");
  EXPECT_EQ(images[1].encoding, "jpeg");
  EXPECT_EQ(images[0].data, images[2].data);
  EXPECT_EQ(images[1].data, images[3].data);
  EXPECT_EQ(images[0].seq, 7);
  EXPECT_EQ(images[0].name, "eye/sm0/camera");
  const CameraPicture jpeg = DecodeCameraImage(images[1]);
  EXPECT_EQ(jpeg.width, 48);
  EXPECT_EQ(jpeg.height, 32);
}

// mrsim-camera with a fixed camera on a static post looking back at the
// ball along -x, rendered for real from the robot's state: the picture
// goes on MRSIM_CAMERA_scene and shows the red ball in its middle.
TEST(CameraNode, AFixedSceneCameraIsPicturedFromTheStatesOnTheSceneChannel) {
  Scenario s = SnakeWithCamera();
  s.robots[0].sensor_modules[0].cameras.clear();
  SceneObject post;
  post.guid = "post";
  post.size = Eigen::Vector3d::Constant(0.04);
  post.position = s.scene_objects[0].position + Eigen::Vector3d(0.5, 0, 0.1);
  post.is_static = true;
  Camera camera;
  camera.sensor_position = 5;  // back: looks along -x, at the ball
  camera.tilt = 11;
  camera.width = 48;
  camera.height = 32;
  post.cameras.push_back(camera);
  s.scene_objects.push_back(post);
  Physics physics(s);
  StateCameraRenderer renderer(s);
  CameraNode node(Options(ClockMode::kLockstep), &renderer, WallTime{});
  CameraOutbox out;
  node.OnState("MRSIM_STATE_eye",
               ToRobotStateMessage(physics.ReadRobotState(0), 3), WallTime{},
               &out);
  ASSERT_EQ(out.messages.size(), 2u);  // the picture, the answer
  EXPECT_EQ(out.messages[0].first, "MRSIM_CAMERA_scene");
  EXPECT_EQ(out.messages[1].first, "MRSIM_COMMAND_eye");
  const auto& image = std::get<camera_image_t>(out.messages[0].second);
  EXPECT_EQ(image.robot, "scene");
  EXPECT_EQ(image.name, "scene/obj1/camera");
  EXPECT_EQ(image.sensor_module, -1);
  EXPECT_EQ(image.seq, 3);
  const CameraPicture picture = DecodeCameraImage(image);
  int red_middle = 0, red_edges = 0;
  for (int y = 0; y < picture.height; ++y) {
    for (int x = 0; x < picture.width; ++x) {
      const std::uint8_t* p =
          &picture.rgb[(static_cast<size_t>(y) * picture.width + x) * 3];
      const bool red = p[0] > 120 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
      if (x >= 18 && x < 30) red_middle += red;
      if (x < 6 || x >= 42) red_edges += red;
    }
  }
  EXPECT_GT(red_middle, 8);
  EXPECT_EQ(red_edges, 0);
}

TEST(CameraNode, AStateThatDoesNotFitTheScenarioIsMalformed) {
  const Scenario s = SnakeWithCamera();
  Physics physics(s);
  StateCameraRenderer renderer(s);
  CameraNode node(Options(ClockMode::kLockstep), &renderer, WallTime{});
  CameraOutbox out;
  robot_state_t state = ToRobotStateMessage(physics.ReadRobotState(0), 0);
  state.frames.pop_back();  // one frame short of the scenario's robot
  state.num_frames = static_cast<int32_t>(state.frames.size());
  node.OnState("MRSIM_STATE_eye", state, WallTime{}, &out);
  state = ToRobotStateMessage(physics.ReadRobotState(0), 0);
  state.com[0] = std::numeric_limits<double>::infinity();
  node.OnState("MRSIM_STATE_eye", state, WallTime{}, &out);
  scene_state_t scene{};
  scene.num_objects = 1;
  scene.object_index = {5};  // no such scene object
  scene.poses.resize(1);
  node.OnScene(scene, WallTime{});
  EXPECT_EQ(node.counters().malformed, 3);
  EXPECT_TRUE(out.empty());
}

// What a reader of camera_image_t (the logger, Python, the studio) relies
// on: hostile pictures are refused with the field named, never trusted.
TEST(CameraNode, HostilePicturesAreRefusedNamingTheField) {
  CameraImageHeader header;
  header.robot = "eye";
  CameraPicture picture{16, 16, std::vector<std::uint8_t>(16 * 16 * 3, 9)};
  const camera_image_t good = EncodeCameraImage(header, picture);
  int refused = 0;
  auto refuse = [&](camera_image_t msg, const std::string& field) {
    try {
      DecodeCameraImage(msg);
      ADD_FAILURE() << "accepted a picture with a bad " << field;
    } catch (const std::invalid_argument& e) {
      ++refused;
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos)
          << e.what();
    }
  };
  camera_image_t m = good;
  m.width = 17;  // bytes disagree with the size
  refuse(m, "width");
  m = good;
  m.width = 100000;
  m.height = 100000;
  refuse(m, "width");
  m = good;
  m.encoding = "png";
  refuse(m, "encoding");
  camera_image_t jpeg = EncodeCameraImage(header, picture, 90);
  jpeg.data.assign(64, 0xd8);  // no JPEG at all
  jpeg.num_bytes = static_cast<int32_t>(jpeg.data.size());
  refuse(jpeg, "data");
  jpeg = EncodeCameraImage(header, picture, 90);
  jpeg.width = jpeg.height = 32;  // a 16x16 JPEG said to be 32x32
  refuse(jpeg, "data");
  m = good;
  m.num_bytes = 5;
  refuse(m, "num_bytes");
  EXPECT_EQ(refused, 6);
  EXPECT_EQ(DecodeCameraImage(good).rgb, picture.rgb);
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

// A loose sensor module's camera is drawn where the loose state of the
// period puts it: the node listens to <prefix>_STATE_loose, keeps the
// newest state not after the period and hands it to the renderer.
TEST(CameraNode, LooseStateOfThePeriodPosesTheLooseParts) {
  FakeRenderer renderer(100);
  renderer.loose_parts = true;
  CameraNode node(Options(ClockMode::kLockstep), &renderer, WallTime{});
  const std::vector<std::string> channels = node.StateChannels();
  EXPECT_NE(std::find(channels.begin(), channels.end(), "MRSIM_STATE_loose"),
            channels.end());
  CameraOutbox out;
  Period(node, 0, &out);
  EXPECT_EQ(renderer.loose_time, -1);  // none heard yet: as built
  for (std::int64_t seq = 1; seq <= 3; ++seq) {
    robot_state_t loose = State(kLooseOwnerName, seq, seq * 0.01);
    loose.joints.clear();
    loose.num_joints = 0;
    loose.sensor_modules.resize(1);
    loose.sensor_modules[0].pose.orientation[0] = 1;
    loose.num_sensor_modules = 1;
    node.OnState("MRSIM_STATE_loose", loose, WallTime{}, &out);
    Period(node, seq, &out);
    EXPECT_DOUBLE_EQ(renderer.loose_time, seq * 0.01);
  }
  EXPECT_EQ(node.counters().malformed, 0) << node.last_error();
  // Not the scenario's loose parts: counted, never drawn.
  robot_state_t bad = State(kLooseOwnerName, 4, 0.04);
  node.OnState("MRSIM_STATE_loose", bad, WallTime{}, &out);
  EXPECT_EQ(node.counters().malformed, 1);
  Period(node, 4, &out);
  EXPECT_DOUBLE_EQ(renderer.loose_time, 0.03);

  FakeRenderer without(100);
  CameraNode plain(Options(ClockMode::kLockstep), &without, WallTime{});
  const std::vector<std::string> plain_channels = plain.StateChannels();
  EXPECT_EQ(std::find(plain_channels.begin(), plain_channels.end(),
                      "MRSIM_STATE_loose"),
            plain_channels.end());
}

}  // namespace
}  // namespace mrsim

namespace mrsim {
namespace {

// Red pixels in columns [x0, x1) of a picture.
int RedPixels(const CameraPicture& picture, int x0, int x1) {
  int red = 0;
  for (int y = 0; y < picture.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p =
          &picture.rgb[(static_cast<size_t>(y) * picture.width + x) * 3];
      red += p[0] > 120 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
    }
  }
  return red;
}

// A loose sensor module's camera built 1 m to the side of the red ball,
// which the simulation has moved in front of it: mrsim-camera pictures it
// from the published loose state, so the ball is in the middle.
TEST(CameraNode, ALooseModulesCameraLooksFromWhereTheLooseStatePutsIt) {
  Scenario s = SnakeWithCamera();
  const SensorModule& head = s.robots[0].sensor_modules[0];
  SensorModule eye;
  eye.guid = "loose eye";
  eye.position = head.position + Eigen::Vector3d(0.2, 1.0, 0);
  Camera camera;
  camera.width = 48;
  camera.height = 32;
  eye.cameras.push_back(camera);
  s.loose_sensor_modules.push_back(eye);
  Physics physics(s);
  StateCameraRenderer renderer(s);
  CameraNodeOptions options = Options(ClockMode::kLockstep);
  options.robot = kLooseOwnerName;
  CameraNode node(options, &renderer, WallTime{});
  CameraOutbox out;
  const robot_state_t robot = ToRobotStateMessage(physics.ReadRobotState(0), 0);
  auto picture = [&]() {
    node.OnState("MRSIM_STATE_eye", robot, WallTime{}, &out);
    EXPECT_EQ(node.counters().malformed, 0) << node.last_error();
    for (const auto& [channel, msg] : out.messages) {
      if (const auto* image = std::get_if<camera_image_t>(&msg)) {
        EXPECT_EQ(channel, "MRSIM_CAMERA_loose");
        return DecodeCameraImage(*image);
      }
    }
    ADD_FAILURE() << "no picture";
    return CameraPicture{};
  };
  // No loose state heard: as built, looking past the ball.
  const CameraPicture built = picture();
  ASSERT_EQ(built.width, 48);
  EXPECT_EQ(RedPixels(built, 0, 48), 0);
  // The loose state has it 1 m over, the ball 0.2 m ahead of it. Each
  // period is a new frame slot: its time is after the last picture's.
  robot_state_t loose = ToRobotStateMessage(physics.ReadLooseState(), 1);
  loose.sensor_modules[0].pose.position[1] -= 1.0;
  loose.sim_time = 1.0;
  loose.utime = 1000000;
  node.OnState("MRSIM_STATE_loose", loose, WallTime{}, &out);
  out.clear();
  robot_state_t r = robot;
  r.seq = 1;
  r.sim_time = 1.0;
  r.utime = 1000000;
  node.OnState("MRSIM_STATE_eye", r, WallTime{}, &out);
  EXPECT_EQ(node.counters().malformed, 0) << node.last_error();
  const camera_image_t* image = nullptr;
  for (const auto& [channel, msg] : out.messages) {
    if (const auto* i = std::get_if<camera_image_t>(&msg)) image = i;
  }
  ASSERT_NE(image, nullptr);
  const CameraPicture moved = DecodeCameraImage(*image);
  EXPECT_GT(RedPixels(moved, 18, 30), 8);
  EXPECT_EQ(RedPixels(moved, 0, 6) + RedPixels(moved, 42, 48), 0);
}

}  // namespace
}  // namespace mrsim
