#include "viewer/renderer.h"

#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace mrsim {
namespace {

constexpr int kMinSize = 16;
constexpr int kMaxSize = 8192;
// Room in the scene for rays and their end markers beyond the model's geoms.
constexpr int kExtraGeoms = 2000;

}  // namespace

Renderer::Renderer(const mjModel* model, int width, int height,
                   const RenderQuality& quality)
    : model_(model), width_(width), height_(height) {
  if (model == nullptr) throw std::invalid_argument("Renderer: null model");
  if (width < kMinSize || width > kMaxSize || height < kMinSize ||
      height > kMaxSize) {
    throw std::invalid_argument(
        "Renderer: frame size " + std::to_string(width) + "x" +
        std::to_string(height) + " outside " + std::to_string(kMinSize) + ".." +
        std::to_string(kMaxSize));
  }
  mjv_defaultScene(&scene_);
  mjv_defaultOption(&option_);
  // Rays come from the state (Ray); MuJoCo's own would read sensordata,
  // which a posed-but-not-simulated mjData does not have.
  option_.flags[mjVIS_RANGEFINDER] = 0;
  mjr_defaultContext(&context_);
  mjv_makeScene(model, &scene_, model->ngeom + kExtraGeoms);
  // mjr_makeContext sizes the off-screen buffer from the model's visual
  // settings; a shallow copy carries ours without touching the caller's.
  mjModel sized = *model;
  sized.vis.global.offwidth = width;
  sized.vis.global.offheight = height;
  if (quality.samples >= 0) sized.vis.quality.offsamples = quality.samples;
  if (quality.shadow_size > 0) {
    sized.vis.quality.shadowsize = quality.shadow_size;
  }
  try {
    // MuJoCo errors throw (mujoco_handlers.h); the scene is ours to free.
    mjr_makeContext(&sized, &context_, mjFONTSCALE_150);
  } catch (...) {
    mjr_freeContext(&context_);
    mjv_freeScene(&scene_);
    throw;
  }
  if (context_.offWidth < width || context_.offHeight < height) {
    // Read the size before freeing: mjr_freeContext zeroes the context.
    const int got_width = context_.offWidth;
    const int got_height = context_.offHeight;
    mjr_freeContext(&context_);
    mjv_freeScene(&scene_);
    throw std::runtime_error(
        "Renderer: the OpenGL context gave a " + std::to_string(got_width) +
        "x" + std::to_string(got_height) + " off-screen buffer, " +
        std::to_string(width) + "x" + std::to_string(height) + " needed");
  }
  if (quality.shadow_size == 0) scene_.flags[mjRND_SHADOW] = 0;
  rgb_.resize(static_cast<size_t>(width) * height * 3);
}

Renderer::~Renderer() {
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
}

void Renderer::BuildScene(mjData* data, const mjvCamera& camera,
                          const std::vector<Ray>& rays) {
  mjvCamera cam = camera;
  mjv_updateScene(model_, data, &option_, nullptr, &cam, mjCAT_ALL, &scene_);
  const float hit_rgba[4] = {1.0f, 0.15f, 0.1f, 1.0f};
  const float miss_rgba[4] = {0.2f, 0.8f, 1.0f, 0.5f};
  for (const Ray& ray : rays) {
    if (scene_.ngeom + 2 > scene_.maxgeom) break;
    if (!ray.from.allFinite() || !ray.to.allFinite()) continue;
    const float* rgba = ray.hit ? hit_rgba : miss_rgba;
    mjvGeom* line = scene_.geoms + scene_.ngeom++;
    mjv_initGeom(line, mjGEOM_CAPSULE, nullptr, nullptr, nullptr, rgba);
    mjv_makeConnector(line, mjGEOM_CAPSULE, 0.002, ray.from.x(), ray.from.y(),
                      ray.from.z(), ray.to.x(), ray.to.y(), ray.to.z());
    line->category = mjCAT_DECOR;
    if (ray.hit) {
      const mjtNum size[3] = {0.008, 0.008, 0.008};
      const mjtNum pos[3] = {ray.to.x(), ray.to.y(), ray.to.z()};
      mjvGeom* dot = scene_.geoms + scene_.ngeom++;
      mjv_initGeom(dot, mjGEOM_SPHERE, size, pos, nullptr, rgba);
      dot->category = mjCAT_DECOR;
    }
  }
}

void Renderer::DrawOverlay(const mjrRect& viewport, const Overlay& overlay) {
  char values[256];
  std::snprintf(values, sizeof(values), "%.3f s\n%.3f m/s%s%s", overlay.time,
                overlay.speed, overlay.gait.empty() ? "" : "\n",
                overlay.gait.c_str());
  const char* titles =
      overlay.gait.empty() ? "time\nspeed" : "time\nspeed\ngait";
  mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, titles, values,
              &context_);
}

void Renderer::Render(mjData* data, const mjvCamera& camera,
                      const std::vector<Ray>& rays, const Overlay* overlay,
                      cv::Mat* bgr) {
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  const mjrRect viewport = {0, 0, width_, height_};
  BuildScene(data, camera, rays);
  mjr_render(viewport, &scene_, &context_);
  if (overlay != nullptr) DrawOverlay(viewport, *overlay);
  mjr_readPixels(rgb_.data(), nullptr, viewport, &context_);
  // OpenGL rows run bottom-up in RGB; OpenCV wants top-down BGR.
  const cv::Mat rgb(height_, width_, CV_8UC3, rgb_.data());
  cv::flip(rgb, flipped_, 0);
  cv::cvtColor(flipped_, *bgr, cv::COLOR_RGB2BGR);
}

void Renderer::RenderToWindow(mjData* data, const mjvCamera& camera,
                              const std::vector<Ray>& rays,
                              const Overlay* overlay, int width, int height) {
  mjr_setBuffer(mjFB_WINDOW, &context_);
  const mjrRect viewport = {0, 0, width, height};
  BuildScene(data, camera, rays);
  mjr_render(viewport, &scene_, &context_);
  if (overlay != nullptr) DrawOverlay(viewport, *overlay);
}

}  // namespace mrsim
