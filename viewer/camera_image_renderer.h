// What a scenario's robot cameras (<Camera> parts of sensor modules) see:
// each camera's picture rendered off-screen by MuJoCo from the poses in an
// mjData (the physics' own, or one StatePoseMapper posed from states),
// with the camera's field of view, size, clipping and seeded pixel noise.
// The one renderer mrsim-camera, Python's Simulation.camera_image and the
// studio share. Needs a current OpenGL context (GlContext or a window).
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// One camera of one robot, numbered as camera_image_t numbers them.
struct RobotCamera {
  int robot = 0;  // index in the scenario's robots
  std::string robot_name;
  int camera = 0;         // index among the robot's cameras
  int sensor_module = 0;  // index of its sensor module in the robot
  std::string name;       // its MuJoCo camera, "<robot>/sm<k>/camera<i>"
  int mj_camera = -1;     // id in the model
  Camera part;
};

// Every camera of the scenario's robots, in robot order, then sensor-module
// order, then each module's <cameras> order.
std::vector<RobotCamera> RobotCameras(const Scenario& scenario);

class CameraImageRenderer {
 public:
  // `model` is BuildMjcf(scenario) compiled and must outlive the renderer.
  // Throws std::runtime_error naming a camera the model lacks, or what
  // OpenGL could not make.
  CameraImageRenderer(const mjModel* model, const Scenario& scenario);
  ~CameraImageRenderer();
  CameraImageRenderer(const CameraImageRenderer&) = delete;
  CameraImageRenderer& operator=(const CameraImageRenderer&) = delete;

  const std::vector<RobotCamera>& cameras() const { return cameras_; }
  // Index in cameras() of robot `robot`'s camera `camera`, or -1.
  int Find(int robot, int camera) const;

  // Renders cameras()[index] from the poses in `data` (cam_xpos/cam_xmat
  // and every geom's; mj_forward or StatePoseMapper::Apply filled them)
  // into `rgb`: height x width x 3 bytes, red first, top row first. `seq`
  // (the state's) keys the pixel noise, so a picture is a function of the
  // state and the camera alone. Throws std::out_of_range for a bad index.
  void Render(int index, mjData* data, std::int64_t seq,
              std::vector<std::uint8_t>* rgb);

 private:
  const mjModel* model_;
  std::vector<RobotCamera> cameras_;
  mjvScene scene_;
  mjvOption option_;
  mjrContext context_;
  std::vector<std::uint8_t> raw_;
};

}  // namespace mrsim
