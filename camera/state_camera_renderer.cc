#include "camera/state_camera_renderer.h"

#include <stdexcept>

#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_data.h"

namespace mrsim {

StateCameraRenderer::StateCameraRenderer(const Scenario& scenario) {
  model_ = CompileScenarioModel(scenario, MjcfOptions{});
  data_ = MakeMjData(model_.get());
  if (data_ == nullptr) throw std::runtime_error("camera: mj_makeData failed");
  mj_forward(model_.get(), data_.get());  // lights and everything built
  mapper_ = std::make_unique<StatePoseMapper>(model_.get(), scenario);
  for (int r = 0; r < mapper_->robot_count(); ++r) {
    robots_.push_back(mapper_->robot_name(r));
  }
  renderer_ = std::make_unique<CameraImageRenderer>(model_.get(), scenario);
  has_loose_parts_ =
      !scenario.loose_frames.empty() || !scenario.loose_sensor_modules.empty();
}

StateCameraRenderer::~StateCameraRenderer() = default;

const std::vector<ScenarioCamera>& StateCameraRenderer::cameras() const {
  return renderer_->cameras();
}

std::string StateCameraRenderer::Check(int robot,
                                       const RobotState& state) const {
  return mapper_->Check(robot, state);
}

std::string StateCameraRenderer::CheckScene(
    const std::vector<SceneObjectState>& scene) const {
  return mapper_->CheckScene(scene);
}

std::string StateCameraRenderer::CheckLoose(const RobotState& loose) const {
  return mapper_->CheckLoose(loose);
}

void StateCameraRenderer::Render(int camera,
                                 const std::vector<const RobotState*>& states,
                                 const std::vector<SceneObjectState>* scene,
                                 const RobotState* loose, std::int64_t seq,
                                 CameraPicture* picture) {
  gl_.MakeCurrent();
  mapper_->Apply(states, data_.get(), scene, loose);
  const Camera& part = renderer_->cameras().at(camera).part;
  picture->width = part.width;
  picture->height = part.height;
  renderer_->Render(camera, data_.get(), seq, &picture->rgb);
}

}  // namespace mrsim
