// Off-screen rendering speed of mrsim_viewer (pose from state, rays,
// overlay, read back to a BGR image) against a bare MuJoCo loop
// (mjv_updateScene + mjr_render + mjr_readPixels) on the same model, same
// GL context, same run. Rounds alternate so load changes hit both alike.
//
// Prints BENCH viewer_fps_ratio <ours / bare> x (target >= 0.9) and the raw
// frame rates: both at the model's render settings, plus the pipeline with
// MP4 encoding and the viewer at mrsim-view's defaults (1024 shadow map).
#include <mujoco/mujoco.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <opencv2/core.hpp>
#include <vector>

#include "sim_core/chain_builder.h"
#include "sim_core/physics.h"
#include "viewer/camera_control.h"
#include "viewer/frame_writer.h"
#include "viewer/gl_context.h"
#include "viewer/state_viewer.h"

namespace mrsim {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr int kRounds = 4;
constexpr int kFramesPerRound = 30;

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

Scenario BenchScenario() {
  ChainOptions chain;
  chain.name = "snake";
  chain.modules = 11;
  chain.pattern = ChainPattern::kPitchYaw;
  chain.sensor_after = {-1, 5};
  chain.force_sensors = true;
  chain.front_distance_sensor = true;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(chain));
  SceneObject ball;
  ball.guid = "ball";
  ball.shape = PrimitiveShape::kSphere;
  ball.size = Eigen::Vector3d(0.1, 0.1, 0.1);
  ball.position = Eigen::Vector3d(0.5, 0.0, 0.05);
  scenario.scene_objects.push_back(ball);
  return scenario;
}

// The bare loop: MuJoCo's own structures, nothing of ours, drawing the
// physics' mjData at the same instants from the same camera.
class BareLoop {
 public:
  explicit BareLoop(const mjModel* model) : model_(model) {
    mjv_defaultScene(&scene_);
    mjv_defaultOption(&option_);
    mjr_defaultContext(&context_);
    mjv_makeScene(model, &scene_, 2000);
    mjModel sized = *model;
    sized.vis.global.offwidth = kWidth;
    sized.vis.global.offheight = kHeight;
    mjr_makeContext(&sized, &context_, mjFONTSCALE_150);
    rgb_.resize(kWidth * kHeight * 3);
  }
  ~BareLoop() {
    mjr_freeContext(&context_);
    mjv_freeScene(&scene_);
  }
  void Frame(mjData* data, mjvCamera* camera) {
    mjr_setBuffer(mjFB_OFFSCREEN, &context_);
    const mjrRect viewport = {0, 0, kWidth, kHeight};
    mjv_updateScene(model_, data, &option_, nullptr, camera, mjCAT_ALL,
                    &scene_);
    mjr_render(viewport, &scene_, &context_);
    mjr_readPixels(rgb_.data(), nullptr, viewport, &context_);
  }

 private:
  const mjModel* model_;
  mjvScene scene_;
  mjvOption option_;
  mjrContext context_;
  std::vector<unsigned char> rgb_;
};

int Run() {
  GlContext gl;
  const Scenario scenario = BenchScenario();
  // States of a moving snake for the viewer to show.
  Physics physics(scenario);
  std::vector<RobotState> states;
  std::vector<MjDataPtr> snapshots;  // the physics at each state
  std::vector<double> targets(physics.joint_count(0));
  for (int k = 0; k < kFramesPerRound; ++k) {
    const double until = physics.time() + 1.0 / 30.0;
    while (physics.time() < until) {
      for (size_t j = 0; j < targets.size(); ++j) {
        targets[j] = 0.8 * std::sin(2 * M_PI * physics.time() + 1.5 * j);
      }
      physics.SetJointTargets(0, targets);
      physics.Step();
    }
    states.push_back(physics.ReadRobotState(0));
    snapshots.emplace_back(
        mj_copyData(nullptr, physics.model(), physics.data()));
  }

  ViewerOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.gait = "forward";
  StateViewer viewer(scenario, options);
  BareLoop bare(physics.model());
  // The viewer's follow camera at each state, for the bare loop.
  std::vector<mjvCamera> cameras;
  CameraControl follow(options.camera);
  for (const RobotState& state : states) {
    follow.Track(state.com);
    cameras.push_back(follow.camera());
  }

  cv::Mat image;
  // Warm up both (first frames upload meshes and textures).
  for (int i = 0; i < 5; ++i) {
    bare.Frame(snapshots[i].get(), &cameras[i]);
    viewer.Render({&states[i]}, &image);
  }
  double bare_s = 0.0;
  double ours_s = 0.0;
  for (int round = 0; round < kRounds; ++round) {
    auto t0 = Clock::now();
    for (int i = 0; i < kFramesPerRound; ++i) {
      bare.Frame(snapshots[i].get(), &cameras[i]);
    }
    auto t1 = Clock::now();
    for (int i = 0; i < kFramesPerRound; ++i) {
      viewer.Render({&states[i]}, &image);
    }
    auto t2 = Clock::now();
    bare_s += Seconds(t0, t1);
    ours_s += Seconds(t1, t2);
    std::fprintf(stderr, "bench_viewer: round %d/%d\n", round + 1, kRounds);
  }
  const double frames = static_cast<double>(kRounds) * kFramesPerRound;
  const double bare_fps = frames / bare_s;
  const double ours_fps = frames / ours_s;

  // mrsim-view's default settings (1024 shadow map instead of 4096).
  ViewerOptions fast_options = options;
  fast_options.quality.shadow_size = 1024;
  StateViewer fast(scenario, fast_options);
  fast.Render({&states[0]}, &image);
  double fast_fps = 0.0;
  {
    auto t0 = Clock::now();
    for (int i = 0; i < kFramesPerRound; ++i) {
      fast.Render({&states[i]}, &image);
    }
    fast_fps = kFramesPerRound / Seconds(t0, Clock::now());
  }

  // The whole pipeline as mrsim-view runs it: render + MP4 encode.
  const std::string video = "/tmp/bench_viewer.mp4";
  double pipeline_fps = 0.0;
  {
    auto writer = FrameWriter::Video(video, 30.0, kWidth, kHeight);
    auto t0 = Clock::now();
    for (int i = 0; i < kFramesPerRound; ++i) {
      viewer.Render({&states[i]}, &image);
      writer->Write(image, i);
    }
    writer->Close();
    pipeline_fps = kFramesPerRound / Seconds(t0, Clock::now());
  }
  std::remove(video.c_str());

  std::printf("# %s; 11-module snake, %dx%d, %d frames each\n",
              gl.description().c_str(), kWidth, kHeight,
              static_cast<int>(frames));
  std::printf("BENCH viewer_bare_fps %.1f frames/s\n", bare_fps);
  std::printf("BENCH viewer_fps %.1f frames/s\n", ours_fps);
  std::printf("BENCH viewer_mp4_pipeline_fps %.1f frames/s\n", pipeline_fps);
  std::printf("BENCH viewer_cli_default_fps %.1f frames/s\n", fast_fps);
  std::printf("BENCH viewer_fps_ratio %.3f x\n", ours_fps / bare_fps);
  return 0;
}

}  // namespace
}  // namespace mrsim

int main() {
  try {
    return mrsim::Run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_viewer: %s\n", e.what());
    return 1;
  }
}
