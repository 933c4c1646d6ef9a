// The viewer's scene: the model rebuilt from a scenario (BuildMjcf), posed
// from robot states, seen by a follow or fixed camera, drawn with rays and
// an overlay. What mrsim-view renders for every frame; needs a current
// OpenGL context (GlContext or LiveWindow).
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"
#include "viewer/camera_control.h"
#include "viewer/renderer.h"
#include "viewer/state_pose_mapper.h"

namespace mrsim {

struct ViewerOptions {
  int width = 640;
  int height = 480;
  CameraSettings camera;
  std::string follow_robot;  // camera and overlay robot; empty: the first
  std::string gait;          // shown in the overlay when not empty
  bool overlay = true;
  bool rays = true;
  RenderQuality quality;
};

class StateViewer {
 public:
  // Builds and compiles the model. Throws std::invalid_argument for an
  // unknown follow robot, std::runtime_error naming what failed otherwise
  // (MJCF compile error, unmatched parts).
  StateViewer(const Scenario& scenario, const ViewerOptions& options);
  ~StateViewer();
  StateViewer(const StateViewer&) = delete;
  StateViewer& operator=(const StateViewer&) = delete;

  int robot_count() const { return mapper_->robot_count(); }
  const std::string& robot_name(int robot) const;
  int robot_index(const std::string& name) const;
  int follow_robot() const { return follow_; }
  // Empty when the state fits the robot; else what is wrong.
  std::string Check(int robot, const RobotState& state) const;

  // Empty when a scene state fits the scenario's movable scene objects.
  std::string CheckScene(const std::vector<SceneObjectState>& scene) const;

  // Poses the model from states[r] (null: as built) and the scene objects
  // from `scene` (null: as built), points a follow camera at the followed
  // robot's centre of mass, renders off-screen into `bgr`.
  void Render(const std::vector<const RobotState*>& states, cv::Mat* bgr,
              const std::vector<SceneObjectState>* scene = nullptr);
  // Draws the scene of the last Render into the current window.
  void RenderToWindow(int width, int height);

  // The gait text of the overlay from now on.
  void set_gait(const std::string& gait) { options_.gait = gait; }
  CameraControl* camera() { return &camera_; }
  const mjModel* model() const { return model_.get(); }
  // The poses of the last Render.
  const mjData* data() const { return data_.get(); }
  Renderer* renderer() { return renderer_.get(); }

 private:
  ViewerOptions options_;
  MjModelPtr model_;
  MjDataPtr data_;
  std::unique_ptr<StatePoseMapper> mapper_;
  std::unique_ptr<Renderer> renderer_;
  CameraControl camera_;
  int follow_ = 0;
  std::vector<Ray> rays_;
  Overlay overlay_;
  bool has_overlay_ = false;
};

}  // namespace mrsim
