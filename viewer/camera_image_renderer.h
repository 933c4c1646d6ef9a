// What a scenario's cameras (<Camera> parts of robots' and loose sensor
// modules and of scene objects) see: each camera's picture rendered
// off-screen by MuJoCo from the poses in an mjData (the physics' own, or
// one StatePoseMapper posed from states), with the camera's field of view,
// size, clipping and seeded pixel noise. The one renderer mrsim-camera,
// Python's Simulation.camera_image and the studio share. Needs a current
// OpenGL context (GlContext or a window).
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// One camera of the scenario, numbered as camera_image_t numbers them:
// from 0 within its owner, the robot it is on, or "loose" (the loose
// sensor modules) or "scene" (the scene objects; kLooseOwnerName,
// kSceneOwnerName). The owner is the message's `robot` and the end of its
// channel, <prefix>_CAMERA_<owner> (docs/camera.md).
struct ScenarioCamera {
  std::string owner;       // robot name, "loose" or "scene"
  int robot = -1;          // index in the scenario's robots; -1: none
  int camera = 0;          // index among the owner's cameras
  int sensor_module = -1;  // its sensor module in the robot or the loose
                           // list; -1 on a scene object
  int scene_object = -1;   // its scene object; -1 on a sensor module
  std::string part_guid;   // guid of its sensor module or scene object
  std::string name;        // its MuJoCo camera, "<owner>/sm<k>/camera<i>"
                           // or "scene/obj<k>/camera<i>"
  int mj_camera = -1;      // id in the model
  Camera part;
};

// Every camera of the scenario: the robots' in robot order, then
// sensor-module order, then each module's <cameras> order; then the loose
// sensor modules' ("loose"), then the scene objects' ("scene"), in the
// same way.
std::vector<ScenarioCamera> ScenarioCameras(const Scenario& scenario);

class CameraImageRenderer {
 public:
  // `model` is BuildMjcf(scenario) compiled and must outlive the renderer.
  // Throws std::runtime_error naming a camera the model lacks, or what
  // OpenGL could not make.
  CameraImageRenderer(const mjModel* model, const Scenario& scenario);
  ~CameraImageRenderer();
  CameraImageRenderer(const CameraImageRenderer&) = delete;
  CameraImageRenderer& operator=(const CameraImageRenderer&) = delete;

  const std::vector<ScenarioCamera>& cameras() const { return cameras_; }
  // Index in cameras() of camera `camera` of `owner` (a robot's name,
  // "loose" or "scene"), or -1.
  int Find(const std::string& owner, int camera) const;

  // Renders cameras()[index] from the poses in `data` (cam_xpos/cam_xmat
  // and every geom's; mj_forward or StatePoseMapper::Apply filled them)
  // into `rgb`: height x width x 3 bytes, red first, top row first. `seq`
  // (the state's) keys the pixel noise, so a picture is a function of the
  // state and the camera alone. Throws std::out_of_range for a bad index.
  void Render(int index, mjData* data, std::int64_t seq,
              std::vector<std::uint8_t>* rgb);

 private:
  const mjModel* model_;
  std::vector<ScenarioCamera> cameras_;
  mjvScene scene_;
  mjvOption option_;
  mjrContext context_;
  std::vector<std::uint8_t> raw_;
};

}  // namespace mrsim
