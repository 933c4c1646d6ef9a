// Shared by the viewer tests: a small snake with a front distance sensor
// facing a box, driven by real MuJoCo so its states move.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sim_core/physics/physics.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"
#include "viewer/renderer.h"
#include "viewer/state_viewer.h"

namespace mrsim::testing {

// 4 pitch-yaw modules, a sensor module in front with a force plate and a
// distance sensor looking at a box 0.3 m ahead.
Scenario ViewerTestScenario();
// Writes the scenario to dir/scenario.xml and returns the path.
std::string WriteTestScenario(const Scenario& scenario, const std::string& dir);

// The view the viewer tests compare frames in: a fixed camera on the snake
// and box, 320x240, no overlay, mrsim-view's default shadow map.
ViewerOptions FixedView();
// mrsim-view's flags for the same view (size, camera), so a live viewer's
// frames can be compared with frames rendered in process.
std::vector<std::string> FixedViewFlags();

// Steps the physics with a travelling wave on the joints until `time`.
void DriveTo(Physics* physics, double time);

// Rays as the physics sees them (sites of the distance sensors, lengths from
// the state), computed independently of the viewer's mapping.
std::vector<Ray> PhysicsRays(const Physics& physics, const RobotState& state);

// Mean absolute difference per channel (0..255) of two BGR images.
double MeanAbsDiff(const cv::Mat& a, const cv::Mat& b);
// Standard deviation of the grey image: ~0 for a blank frame.
double GreyStdDev(const cv::Mat& bgr);

}  // namespace mrsim::testing
