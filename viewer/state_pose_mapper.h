// Places a compiled scenario model in the poses a robot-state stream
// reports, without running physics: every body gets its world pose (from the
// state, rigidly attached to a body from the state, or as built), then geoms,
// sites and lights follow. Works whatever the body tree of the MJCF is.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "sim_core/physics/scene_object_state.h"
#include "sim_core/scenario/robot_state.h"
#include "sim_core/scenario/scenario.h"
#include "viewer/renderer.h"

namespace mrsim {

class StatePoseMapper {
 public:
  // `model` is BuildMjcf(scenario) compiled; it must outlive the mapper.
  // Bodies are matched to scenario parts by their mjcf_names (else by
  // guid as a body or geom name); bodies below them in the tree move with
  // them. Robot names are mjcf_names::RobotName. Throws
  // std::runtime_error when a robot's frame or sensor module has no body.
  StatePoseMapper(const mjModel* model, const Scenario& scenario);

  int robot_count() const { return static_cast<int>(robots_.size()); }
  const std::string& robot_name(int robot) const;
  // Index of the robot with this name, or -1.
  int robot_index(const std::string& name) const;

  // Empty when `state` fits robot `robot` (part counts, finite numbers);
  // otherwise what is wrong, for a malformed-message count.
  std::string Check(int robot, const RobotState& state) const;

  // Empty when every object of a scene state is a movable scene object of
  // the scenario (each at most once) with a finite pose; else what is wrong.
  std::string CheckScene(const std::vector<SceneObjectState>& scene) const;

  // Empty when `loose` fits the scenario's loose parts (the state mrsim-sim
  // publishes on <prefix>_STATE_loose: a frame per loose frame, a sensor
  // module per loose sensor module, finite poses); else what is wrong.
  std::string CheckLoose(const RobotState& loose) const;

  // Poses every body: robot r from states[r] (null: as built), the scene
  // objects listed in `scene` from it (null or unlisted: as built), the
  // loose frames and sensor modules from `loose` (null: as built),
  // everything else as built. Fills xpos, xquat, xmat, xipos, geom_*,
  // site_*, lights and cameras; `data` must have seen one mj_forward.
  // States must pass Check, the scene CheckScene, loose CheckLoose.
  void Apply(const std::vector<const RobotState*>& states, mjData* data,
             const std::vector<SceneObjectState>* scene = nullptr,
             const RobotState* loose = nullptr) const;

  // The distance-sensor rays of a robot in the pose of the last Apply, each
  // as long as the distance the state reports.
  std::vector<Ray> Rays(int robot, const RobotState& state,
                        const mjData* data) const;

 private:
  struct Pose {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  };
  // Where a body's pose comes from on each Apply.
  struct BodySource {
    enum Kind { kBuilt, kState, kAttached, kScene, kLoose } kind = kBuilt;
    int robot = -1;
    // kState, kLoose: frames then sensor modules, flat; kScene: object
    int part = -1;
    int anchor = -1;  // kAttached: body id of a kState body
    Pose offset;      // kState: body in part frame; kAttached: in anchor frame
  };
  struct RaySource {
    int sensor_module = 0;
    int index = 0;      // in the sensor module's distance list
    int site = -1;      // site the ray starts from, or -1
    int site_axis = 0;  // column of the site frame along the ray
    Eigen::Vector3d local_origin = Eigen::Vector3d::Zero();  // fallback
    Eigen::Vector3d local_direction = Eigen::Vector3d::UnitX();
    double max_distance = 0.0;
  };
  struct RobotInfo {
    std::string name;
    int modules = 0;
    int sensor_modules = 0;
    std::vector<RaySource> rays;
  };

  const mjModel* model_;
  std::vector<RobotInfo> robots_;
  std::vector<BodySource> sources_;  // per body
  std::vector<Pose> built_;          // per body, at qpos0
  // Per scenario scene object: its body when movable, else -1.
  std::vector<int> scene_bodies_;
  int loose_frames_ = 0;
  int loose_sensor_modules_ = 0;
};

}  // namespace mrsim
