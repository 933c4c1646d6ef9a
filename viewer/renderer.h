// Draws a MuJoCo model with MuJoCo's renderer into an off-screen buffer (and
// optionally the current window), adding distance-sensor rays and a text
// overlay. Needs a current OpenGL context (GlContext or a window).
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace mrsim {

// A distance-sensor ray from the sensor to what it measured.
struct Ray {
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
  bool hit = false;  // false: nothing within range (drawn dimmer)
};

// Text in the frame's top-left corner.
struct Overlay {
  double time = 0.0;   // s, simulation time
  double speed = 0.0;  // m/s, centre-of-mass speed
  std::string gait;    // empty: line left out
};

// Costly render features. -1 keeps the model's own <visual><quality>
// (MuJoCo's defaults: 4 samples, 4096 shadow map). On a software renderer
// (llvmpipe) shadows and multisampling dominate the frame time.
struct RenderQuality {
  int samples = -1;      // multisample anti-aliasing samples, 0 = none
  int shadow_size = -1;  // shadow map size in pixels, 0 = no shadows
};

class Renderer {
 public:
  // Off-screen frames are width x height pixels. Throws std::invalid_argument
  // for sizes outside [16, 8192].
  Renderer(const mjModel* model, int width, int height,
           const RenderQuality& quality = RenderQuality());
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders `data` as seen from `camera` off-screen and reads the image back
  // into `bgr` (CV_8UC3, top row first). `overlay` may be null.
  void Render(mjData* data, const mjvCamera& camera,
              const std::vector<Ray>& rays, const Overlay* overlay,
              cv::Mat* bgr);
  // Renders the same into the window framebuffer of the current context
  // (width x height pixels); the caller swaps buffers.
  void RenderToWindow(mjData* data, const mjvCamera& camera,
                      const std::vector<Ray>& rays, const Overlay* overlay,
                      int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  mjvOption* mutable_option() { return &option_; }

 private:
  void BuildScene(mjData* data, const mjvCamera& camera,
                  const std::vector<Ray>& rays);
  void DrawOverlay(const mjrRect& viewport, const Overlay& overlay);

  const mjModel* model_;
  int width_;
  int height_;
  mjvScene scene_;
  mjvOption option_;
  mjrContext context_;
  std::vector<unsigned char> rgb_;
  cv::Mat flipped_;
};

}  // namespace mrsim
