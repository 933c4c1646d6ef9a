// Where things sit on a sensor module's faces, in the module's own frame:
// the one geometry the validator, the MJCF builder, the physics and the
// studio share (no MJCF in here).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Outward normal of a sensor module face in the module's own frame (the
// chain runs along +x, z up): 0 bottom -z, 1 left +y, 2 top +z, 3 right -y,
// 4 front +x, 5 back -x. Force plates use 0..3, distance sensors 0..5.
// Throws std::out_of_range for anything else.
Eigen::Vector3d SensorFaceNormal(int sensor_position);

// Where the physics puts a sensor module's force plate, in the module's
// own frame: flat on its face (sensorPosition), outside the module, its
// thickness (size.z) along the face normal. The plate's own position in
// the file is not used. Throws std::out_of_range as SensorFaceNormal.
struct PlatePose {
  Eigen::Vector3d position;
  Eigen::Quaterniond rotation;
};
PlatePose ForcePlatePose(const SensorModule& sm);

// Where a camera sits on a face (camera.sensor_position) of a box of full
// extents `size` centred on its part's origin (a sensor module, or the box
// around a scene object): at the face's centre, in MuJoCo's camera frame (x
// right, y up, looking along -z) looking out along the face's normal, its
// picture's up the part's +z (for the top and bottom faces its +x), turned
// down by camera.tilt. Throws std::out_of_range as SensorFaceNormal.
struct CameraPose {
  Eigen::Vector3d position;
  Eigen::Quaterniond rotation;
};
CameraPose CameraOnFace(const Camera& camera, const Eigen::Vector3d& size);

// The full extents of the box around a scene object, whose faces its
// cameras sit on: a Box's size; a sphere's diameter (size.x) on every axis;
// a cylinder's or capsule's diameter (size.x) across and length (size.z)
// along z. The sphere, cylinder and capsule touch each face at its centre,
// so a camera there sits on the object's surface.
Eigen::Vector3d SceneObjectBox(const SceneObject& object);

}  // namespace mrsim
