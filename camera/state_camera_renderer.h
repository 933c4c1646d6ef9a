// The renderer of mrsim-camera: the scenario's model posed from decoded
// states (StatePoseMapper, no physics) and drawn off-screen by the shared
// CameraImageRenderer in its own EGL context (no display needed).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "camera/camera_frame_renderer.h"
#include "sim_core/mujoco/mujoco_ptr.h"
#include "sim_core/scenario/scenario.h"
#include "viewer/gl_context.h"
#include "viewer/state_pose_mapper.h"

namespace mrsim {

class StateCameraRenderer : public CameraFrameRenderer {
 public:
  // Compiles the scenario's model and makes an OpenGL context current on
  // the calling thread (Render must run on it). Throws std::runtime_error
  // when the model, the context or a camera cannot be made.
  explicit StateCameraRenderer(const Scenario& scenario);
  ~StateCameraRenderer() override;

  const std::vector<std::string>& robots() const override { return robots_; }
  const std::vector<ScenarioCamera>& cameras() const override;
  std::string Check(int robot, const RobotState& state) const override;
  std::string CheckScene(
      const std::vector<SceneObjectState>& scene) const override;
  bool has_loose_parts() const override { return has_loose_parts_; }
  std::string CheckLoose(const RobotState& loose) const override;
  void Render(int camera, const std::vector<const RobotState*>& states,
              const std::vector<SceneObjectState>* scene,
              const RobotState* loose, std::int64_t seq,
              CameraPicture* picture) override;

 private:
  std::vector<std::string> robots_;
  bool has_loose_parts_ = false;
  GlContext gl_;
  MjModelPtr model_;
  MjDataPtr data_;
  std::unique_ptr<StatePoseMapper> mapper_;
  std::unique_ptr<CameraImageRenderer> renderer_;
};

}  // namespace mrsim
