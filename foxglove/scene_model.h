// What Foxglove's 3-D panel draws of a simulation, made from the messages
// mrsim-sim publishes: each robot's frames and sensor modules as cubes, the
// movable scene objects as spheres and a ground plane, each an entity of a
// foxglove.SceneUpdate in a frame of its own ("<robot>/frame_<k>",
// "<robot>/sensor_<k>", "scene/object_<i>", children of "world"), moved by
// foxglove.FrameTransforms. The states carry poses, not shapes, so a
// frame's cube is sized from the robot's own spacing (the distance between
// the first module's two frames) and scene objects are drawn as 10 cm
// spheres.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "lcmtypes/json/json_writer.h"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"

namespace mrsim::foxglove {

class SceneModel {
 public:
  // Most robots drawn (their states beyond are only forwarded as JSON).
  static constexpr size_t kMaxRobots = 256;

  // Takes a robot's state. True when the scene's shape changed (a new
  // robot, another number of frames or sensor modules): a SceneUpdate is
  // due.
  bool OnRobotState(const robot_state_t& state);
  bool OnSceneState(const scene_state_t& state);

  // The whole scene (deleting what was drawn before), at `time_ns`.
  std::string SceneUpdateJson(uint64_t time_ns) const;
  // The poses of a robot's frames and sensor modules / of the scene
  // objects, at `time_ns`.
  std::string_view FrameTransformsJson(const robot_state_t& state,
                                       uint64_t time_ns);
  std::string_view FrameTransformsJson(const scene_state_t& state,
                                       uint64_t time_ns);

  static std::string FrameName(const std::string& robot, int k);
  static std::string SensorName(const std::string& robot, int k);
  static std::string ObjectName(int index);

 private:
  struct Robot {
    int frames = 0;
    int sensors = 0;
    double edge = 0.05;  // m
  };
  std::map<std::string, Robot> robots_;
  std::map<int32_t, bool> objects_;  // scenario index
  JsonWriter json_;
};

}  // namespace mrsim::foxglove
