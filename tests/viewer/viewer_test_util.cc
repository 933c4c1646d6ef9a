#include "tests/viewer/viewer_test_util.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "sim_core/scenario/chain_builder.h"
#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim::testing {

Scenario ViewerTestScenario() {
  ChainOptions chain;
  chain.name = "snake";
  chain.modules = 4;
  chain.pattern = ChainPattern::kPitchYaw;
  chain.sensor_after = {-1};
  chain.force_sensors = true;
  chain.front_distance_sensor = true;
  Scenario scenario;
  scenario.robots.push_back(MakeChain(chain));
  SceneObject box;
  box.guid = "box";
  box.shape = PrimitiveShape::kBox;
  box.size = Eigen::Vector3d(0.1, 0.4, 0.2);
  box.position = Eigen::Vector3d(0.4, 0.0, 0.1);
  box.is_static = true;
  box.mass = 1.0;
  scenario.scene_objects.push_back(box);
  return scenario;
}

std::string WriteTestScenario(const Scenario& scenario,
                              const std::string& dir) {
  const std::string path = dir + "/scenario.xml";
  WriteScenarioFile(scenario, path);
  return path;
}

ViewerOptions FixedView() {
  ViewerOptions options;
  options.width = 320;
  options.height = 240;
  options.camera.mode = CameraMode::kFixed;
  options.camera.lookat = Eigen::Vector3d(0.1, 0.0, 0.05);
  options.camera.distance = 0.9;
  options.camera.azimuth = 120;
  options.camera.elevation = -30;
  options.overlay = false;
  options.quality.shadow_size = 1024;  // mrsim-view's default
  return options;
}

std::vector<std::string> FixedViewFlags() {
  const ViewerOptions v = FixedView();
  const auto number = [](double x) { return fmt::format("{}", x); };
  const Eigen::Vector3d& at = v.camera.lookat;
  return {"--width",     std::to_string(v.width),
          "--height",    std::to_string(v.height),
          "--camera",    "fixed",
          "--lookat",    fmt::format("{},{},{}", at.x(), at.y(), at.z()),
          "--distance",  number(v.camera.distance),
          "--azimuth",   number(v.camera.azimuth),
          "--elevation", number(v.camera.elevation)};
}

void DriveTo(Physics* physics, double time) {
  const int robot = 0;
  const int joints = physics->joint_count(robot);
  std::vector<double> targets(joints);
  while (physics->time() < time) {
    const double t = physics->time();
    for (int j = 0; j < joints; ++j) {
      targets[j] = 0.8 * std::sin(2 * M_PI * t / 1.0 + 1.5 * j);
    }
    physics->SetJointTargets(robot, targets);
    physics->Step();
  }
}

std::vector<Ray> PhysicsRays(const Physics& physics, const RobotState& state) {
  std::vector<Ray> rays;
  const mjModel* m = physics.model();
  const mjData* d = physics.data();
  const Robot& robot = physics.scenario().robots[0];
  for (size_t s = 0; s < robot.sensor_modules.size(); ++s) {
    const SensorModule& sm = robot.sensor_modules[s];
    for (size_t k = 0; k < sm.distance_sensors.size(); ++k) {
      const std::string name = mjcf_names::DistanceSite(
          robot.name, static_cast<int>(s), static_cast<int>(k));
      const int site = mj_name2id(m, mjOBJ_SITE, name.c_str());
      if (site < 0) continue;
      const double max = sm.distance_sensors[k].max_ray_distance;
      double dist = state.sensor_modules[s].distances[k];
      Ray ray;
      ray.hit = dist >= 0 && dist < max - 1e-9;
      if (!ray.hit) dist = max;
      const mjtNum* xmat = d->site_xmat + 9 * site;
      ray.from = Eigen::Vector3d(d->site_xpos + 3 * site);
      ray.to = ray.from + dist * Eigen::Vector3d(xmat[0], xmat[3], xmat[6]);
      rays.push_back(ray);
    }
  }
  return rays;
}

double MeanAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  const cv::Scalar mean = cv::mean(diff);
  return (mean[0] + mean[1] + mean[2]) / 3.0;
}

double GreyStdDev(const cv::Mat& bgr) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::Scalar mean, stddev;
  cv::meanStdDev(grey, mean, stddev);
  return stddev[0];
}

}  // namespace mrsim::testing
