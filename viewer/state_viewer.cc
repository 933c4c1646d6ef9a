#include "viewer/state_viewer.h"

#include <cstring>
#include <stdexcept>

#include "sim_core/mjcf/model_compiler.h"
#include "sim_core/mujoco/mujoco_data.h"

namespace mrsim {

StateViewer::StateViewer(const Scenario& scenario, const ViewerOptions& options)
    : options_(options), camera_(options.camera) {
  if (scenario.robots.empty()) {
    throw std::runtime_error("viewer: the scenario has no robot to show");
  }
  model_ = CompileScenarioModel(scenario, MjcfOptions{});
  data_ = MakeMjData(model_.get());
  if (data_ == nullptr) throw std::runtime_error("viewer: mj_makeData failed");
  mj_forward(model_.get(), data_.get());  // lights, cameras, everything
  mapper_ = std::make_unique<StatePoseMapper>(model_.get(), scenario);
  if (!options.follow_robot.empty()) {
    follow_ = mapper_->robot_index(options.follow_robot);
    if (follow_ < 0) {
      std::string names;
      for (const Robot& r : scenario.robots) {
        names += (names.empty() ? "" : ", ") + r.name;
      }
      throw std::invalid_argument("viewer: --robot '" + options.follow_robot +
                                  "' is not a robot of the scenario (it has " +
                                  names + ")");
    }
  }
  renderer_ = std::make_unique<Renderer>(model_.get(), options.width,
                                         options.height, options.quality);
}

StateViewer::~StateViewer() = default;

const std::string& StateViewer::robot_name(int robot) const {
  return mapper_->robot_name(robot);
}

int StateViewer::robot_index(const std::string& name) const {
  return mapper_->robot_index(name);
}

std::string StateViewer::Check(int robot, const RobotState& state) const {
  return mapper_->Check(robot, state);
}

std::string StateViewer::CheckScene(
    const std::vector<SceneObjectState>& scene) const {
  return mapper_->CheckScene(scene);
}

void StateViewer::Render(const std::vector<const RobotState*>& states,
                         cv::Mat* bgr,
                         const std::vector<SceneObjectState>* scene) {
  mapper_->Apply(states, data_.get(), scene);
  rays_.clear();
  if (options_.rays) {
    for (int r = 0; r < robot_count() && r < static_cast<int>(states.size());
         ++r) {
      if (states[r] == nullptr) continue;
      std::vector<Ray> rays = mapper_->Rays(r, *states[r], data_.get());
      rays_.insert(rays_.end(), rays.begin(), rays.end());
    }
  }
  const RobotState* followed =
      follow_ < static_cast<int>(states.size()) ? states[follow_] : nullptr;
  if (followed != nullptr) camera_.Track(followed->com);
  has_overlay_ = options_.overlay;
  overlay_ = Overlay();
  overlay_.gait = options_.gait;
  if (followed != nullptr) {
    overlay_.time = followed->time;
    overlay_.speed = followed->com_velocity.norm();
  }
  renderer_->Render(data_.get(), camera_.camera(), rays_,
                    has_overlay_ ? &overlay_ : nullptr, bgr);
}

void StateViewer::RenderToWindow(int width, int height) {
  renderer_->RenderToWindow(data_.get(), camera_.camera(), rays_,
                            has_overlay_ ? &overlay_ : nullptr, width, height);
}

}  // namespace mrsim
