// Small scenarios built in code for the physics tests.
#pragma once

#include <mujoco/mujoco.h>

#include <string>

#include "sim_core/scenario/scenario.h"

namespace mrsim::testing {

// A robot made of one sensor module (a box of `size`, `mass`) centred at
// `position`, no modules.
Robot SensorModuleRobot(const std::string& name,
                        const Eigen::Vector3d& position, double mass = 0.05,
                        const Eigen::Vector3d& size = Eigen::Vector3d(0.05,
                                                                      0.05,
                                                                      0.05));

// One module lying along x with its hinge at `hinge`: frame 0 (+x side)
// static, frame 1 free to turn about the module axis.
Robot CantileverModule(const std::string& name, const Eigen::Vector3d& hinge,
                       Axis axis, double kp, double max_vel, double limit);

// A scenario with a flat ground plane and a material pair for "plastic" on
// "ground".
Scenario FlatScenario();

// How many geoms of the model's bodies (not the world's) collide.
int CollidingRobotGeoms(const mjModel* m);

// Writes a grey PNG (rows x cols, pixel values from `pixel(r, c)`) and
// returns its path.
template <typename F>
std::string WriteGreyPng(const std::string& path, int rows, int cols, F pixel);

}  // namespace mrsim::testing

#include "tests/physics/test_scenes_inl.h"
