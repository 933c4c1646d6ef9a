#include "viewer/camera_image_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/hash.h"
#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/scenario/sensor_kind.h"

namespace mrsim {

namespace {

// The cameras of one owner's sensor modules (a robot's, or the loose ones).
void AddSensorModuleCameras(const std::vector<SensorModule>& sensor_modules,
                            const std::string& owner, int robot,
                            std::vector<ScenarioCamera>* out) {
  int n = 0;
  for (size_t k = 0; k < sensor_modules.size(); ++k) {
    const SensorModule& sm = sensor_modules[k];
    for (size_t i = 0; i < sm.cameras.size(); ++i) {
      ScenarioCamera c;
      c.owner = owner;
      c.robot = robot;
      c.camera = n++;
      c.sensor_module = static_cast<int>(k);
      c.part_guid = sm.guid;
      c.name = mjcf_names::SensorKindSite(owner, static_cast<int>(k), "camera",
                                          static_cast<int>(i));
      c.part = sm.cameras[i];
      out->push_back(std::move(c));
    }
  }
}

}  // namespace

std::vector<ScenarioCamera> ScenarioCameras(const Scenario& scenario) {
  std::vector<ScenarioCamera> out;
  for (size_t r = 0; r < scenario.robots.size(); ++r) {
    AddSensorModuleCameras(scenario.robots[r].sensor_modules,
                           mjcf_names::RobotName(scenario, static_cast<int>(r)),
                           static_cast<int>(r), &out);
  }
  AddSensorModuleCameras(scenario.loose_sensor_modules,
                         mjcf_names::LooseRobot(), -1, &out);
  int n = 0;
  for (size_t o = 0; o < scenario.scene_objects.size(); ++o) {
    const SceneObject& object = scenario.scene_objects[o];
    for (size_t i = 0; i < object.cameras.size(); ++i) {
      ScenarioCamera c;
      c.owner = kSceneOwnerName;
      c.camera = n++;
      c.scene_object = static_cast<int>(o);
      c.part_guid = object.guid;
      c.name = mjcf_names::SceneObjectCamera(static_cast<int>(o),
                                             static_cast<int>(i));
      c.part = object.cameras[i];
      out.push_back(std::move(c));
    }
  }
  return out;
}

CameraImageRenderer::CameraImageRenderer(const mjModel* model,
                                         const Scenario& scenario)
    : model_(model), cameras_(ScenarioCameras(scenario)) {
  if (model == nullptr) {
    throw std::invalid_argument("CameraImageRenderer: null model");
  }
  int width = 16, height = 16;
  for (ScenarioCamera& c : cameras_) {
    c.mj_camera = mj_name2id(model, mjOBJ_CAMERA, c.name.c_str());
    if (c.mj_camera < 0) {
      throw std::runtime_error("camera '" + c.name + "' is not in the model");
    }
    width = std::max(width, c.part.width);
    height = std::max(height, c.part.height);
  }
  mjv_defaultScene(&scene_);
  mjv_defaultOption(&option_);
  // A camera sees the world, not the tools' markers: no sites (its own
  // frustum among them), no rangefinder rays.
  for (int g = 0; g < mjNGROUP; ++g) option_.sitegroup[g] = 0;
  option_.flags[mjVIS_RANGEFINDER] = 0;
  mjr_defaultContext(&context_);
  mjv_makeScene(model, &scene_, model->ngeom + 100);
  // One off-screen buffer as large as the largest picture; each camera
  // draws into its own corner of it. No multisampling: a camera's pixels
  // are samples, and on the CPU it would cost four times the fill.
  mjModel sized = *model;
  sized.vis.global.offwidth = width;
  sized.vis.global.offheight = height;
  sized.vis.quality.offsamples = 0;
  sized.vis.quality.shadowsize = 1024;
  try {
    mjr_makeContext(&sized, &context_, mjFONTSCALE_100);
  } catch (...) {
    mjr_freeContext(&context_);
    mjv_freeScene(&scene_);
    throw;
  }
  if (context_.offWidth < width || context_.offHeight < height) {
    const int got_width = context_.offWidth, got_height = context_.offHeight;
    mjr_freeContext(&context_);
    mjv_freeScene(&scene_);
    throw std::runtime_error(
        "the OpenGL context gave a " + std::to_string(got_width) + "x" +
        std::to_string(got_height) + " off-screen buffer, " +
        std::to_string(width) + "x" + std::to_string(height) + " needed");
  }
}

CameraImageRenderer::~CameraImageRenderer() {
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
}

int CameraImageRenderer::Find(const std::string& owner, int camera) const {
  for (size_t i = 0; i < cameras_.size(); ++i) {
    if (cameras_[i].owner == owner && cameras_[i].camera == camera) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

void CameraImageRenderer::Render(int index, mjData* data, std::int64_t seq,
                                 std::vector<std::uint8_t>* rgb) {
  const ScenarioCamera& c = cameras_.at(static_cast<size_t>(index));
  const int w = c.part.width, h = c.part.height;
  mjvCamera cam;
  mjv_defaultCamera(&cam);
  cam.type = mjCAMERA_FIXED;
  cam.fixedcamid = c.mj_camera;
  // mjv_updateScene places the headlight from the scene's camera before it
  // moves that camera to `cam`: without this, a picture would be lit from
  // wherever the previous one was taken (another camera's pose), so the
  // same state would not always give the same picture.
  mjv_updateCamera(model_, data, &cam, &scene_);
  mjv_updateScene(model_, data, &option_, nullptr, &cam, mjCAT_ALL, &scene_);
  // The camera's own clipping planes (MuJoCo's are one pair for the whole
  // model, in units of its extent); the frustum keeps its field of view.
  const double half = std::tan(c.part.fovy * M_PI / 360);
  for (int eye = 0; eye < 2; ++eye) {
    mjvGLCamera& gl = scene_.camera[eye];
    gl.frustum_near = static_cast<float>(c.part.near_clip);
    gl.frustum_far = static_cast<float>(c.part.far_clip);
    gl.frustum_top = static_cast<float>(c.part.near_clip * half);
    gl.frustum_bottom = -gl.frustum_top;
    gl.frustum_center = 0;
  }
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  const mjrRect viewport = {0, 0, w, h};
  mjr_render(viewport, &scene_, &context_);
  raw_.resize(static_cast<size_t>(w) * h * 3);
  mjr_readPixels(raw_.data(), nullptr, viewport, &context_);
  // OpenGL's rows run bottom-up.
  rgb->resize(raw_.size());
  const size_t row = static_cast<size_t>(w) * 3;
  for (int y = 0; y < h; ++y) {
    std::memcpy(rgb->data() + row * y, raw_.data() + row * (h - 1 - y), row);
  }
  if (c.part.noise > 0) {
    // The same seed, owner, camera and state give the same noise (a
    // robot by its index, the loose parts and the scene by their names).
    const std::uint64_t owner = c.robot >= 0
                                    ? static_cast<std::uint64_t>(c.robot)
                                    : Fnv1a64(c.owner.data(), c.owner.size());
    const std::uint64_t ids[4] = {static_cast<std::uint64_t>(c.part.seed),
                                  owner, static_cast<std::uint64_t>(c.camera),
                                  static_cast<std::uint64_t>(seq)};
    const std::uint64_t key = Fnv1a64(ids, sizeof ids);
    for (size_t i = 0; i < rgb->size(); ++i) {
      const double v =
          (*rgb)[i] + c.part.noise * StandardNormal(key, static_cast<int>(i));
      (*rgb)[i] =
          static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
    }
  }
}

}  // namespace mrsim
