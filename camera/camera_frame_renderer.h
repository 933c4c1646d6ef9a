// What CameraNode needs from a renderer: the scenario's robots and cameras,
// the checks a decoded state must pass before it may pose the model, and a
// picture of one camera from the states of one control period. The real
// one is StateCameraRenderer (MuJoCo, EGL); unit tests give a fake.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"
#include "sim_core/physics/scene_object_state.h"
#include "sim_core/scenario/robot_state.h"
#include "viewer/camera_image_renderer.h"

namespace mrsim {

class CameraFrameRenderer {
 public:
  virtual ~CameraFrameRenderer() = default;

  // The scenario's robot names, in scenario order.
  virtual const std::vector<std::string>& robots() const = 0;
  // Every camera of the scenario (ScenarioCameras order).
  virtual const std::vector<ScenarioCamera>& cameras() const = 0;
  // Empty when `state` fits robot `robot` (StatePoseMapper::Check), else
  // what is wrong.
  virtual std::string Check(int robot, const RobotState& state) const = 0;
  // Empty when `scene` fits the scenario's movable scene objects.
  virtual std::string CheckScene(
      const std::vector<SceneObjectState>& scene) const = 0;
  // Whether the scenario has loose frames or sensor modules, whose state
  // mrsim-sim publishes on <prefix>_STATE_loose.
  virtual bool has_loose_parts() const { return false; }
  // Empty when `loose` fits the scenario's loose parts, else what is wrong.
  virtual std::string CheckLoose(const RobotState& loose) const {
    (void)loose;
    return "";
  }
  // cameras()[camera]'s picture with robot r posed from states[r] (null:
  // as built), the scene objects from `scene` and the loose parts from
  // `loose` (null: as built). `seq` keys the pixel noise.
  virtual void Render(int camera, const std::vector<const RobotState*>& states,
                      const std::vector<SceneObjectState>* scene,
                      const RobotState* loose, std::int64_t seq,
                      CameraPicture* picture) = 0;
};

}  // namespace mrsim
