// The schema table itself: one Describe() per part lists its fields and
// children in file order. A visitor V provides
//   void Field(const FieldInfo&, T& member)        T: a FieldPtr type
//   void Child(const ChildInfo&, P& part)          ChildCount::kOne
//   void Optional(const ChildInfo&, std::optional<P>& part)
//   void Array(const ChildInfo&, std::array<P, N>& parts)
//   void List(const ChildInfo&, std::vector<P>& parts)  kList / kRepeated
//   void Unsupported(const ChildInfo&)  an element of the original's files
//                                       mrsim does not model
// and walks into children by calling Describe(visitor, child) itself.
// Included by the reader, writer, validator and converters; every scenario
// field is named here and nowhere else.
#pragma once

#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "sim_core/scenario/reality_gap_limits.h"
#include "sim_core/scenario/scenario_schema.h"
#include "sim_core/scenario/sensor_face.h"

namespace mrsim {
namespace schema {

using L = FieldLimits;
using G = Geometry;

inline ChildInfo Wrapper(const char* xml, const char* item, const char* member,
                         const char* help, bool assembly = true) {
  ChildInfo c{xml, item, member, help};
  c.assembly = assembly;
  return c;
}

template <typename V>
void DescribePose(V& v, Eigen::Vector3d& position, Eigen::Vector3d& rotation,
                  Eigen::Quaterniond& quat) {
  static const FieldInfo kPosition{
      "position",      "centre position",        "position", "m",
      L::Coordinate(), "Position of the centre", false,      G::kLengthVector};
  static const FieldInfo kRotation{
      "rotation",
      "Euler angles as stored",
      "rotation",
      "deg",
      L::Any(),
      "Euler angles as the original stored them (quatRotation is what "
      "places the part)",
      false,
      G::kEuler};
  static const FieldInfo kQuat{"quatRotation",
                               "orientation",
                               "quat_rotation",
                               "",
                               L::NonZero(),
                               "Orientation as a quaternion; (0,0,0,0) in a "
                               "file means none given (identity)",
                               false,
                               G::kQuaternion};
  v.Field(kPosition, position);
  v.Field(kRotation, rotation);
  v.Field(kQuat, quat);
}

template <typename V>
void Describe(V& v, Frame& f) {
  static const FieldInfo kGuid{"guid",        "id",
                               "guid",        "",
                               L::NonEmpty(), "Unique id joints refer to",
                               true,          Geometry::kNone,
                               false,         true};
  static const FieldInfo kShape{
      "shape",
      "Box or mesh file",
      "shape",
      "",
      L::NonEmpty(),
      "Box, or a mesh file (.obj or .stl) relative to the scenario file"};
  static const FieldInfo kScale{"scale",
                                "scale",
                                "scale",
                                "m",
                                L::Size(),
                                "Box: full extents; mesh: scale of its "
                                "vertices. One number means the same on x, "
                                "y and z",
                                false,
                                G::kLengthVector,
                                true};
  static const FieldInfo kMass{
      "mass", "mass",    "mass",
      "kg",   L::Mass(), "Mass of the frame (static frames too)"};
  static const FieldInfo kStatic{
      "isStatic", "fixed in place", "is_static",
      "",         L::Any(),         "Fixed to the world where it is placed"};
  static const FieldInfo kMaterial{
      "materialName",
      "material",
      "material_name",
      "",
      L::Any(),
      "Material name; ContactFriction pairs give its contact parameters"};
  v.Field(kGuid, f.guid);
  v.Field(kShape, f.shape);
  v.Field(kScale, f.scale);
  DescribePose(v, f.position, f.rotation, f.quat_rotation);
  v.Field(kMass, f.mass);
  v.Field(kStatic, f.is_static);
  v.Field(kMaterial, f.material_name);
}

template <typename V>
void Describe(V& v, Joint& j) {
  static const FieldInfo kGuid{"guid",        "joint id",
                               "guid",        "",
                               L::NonEmpty(), "Unique id of the joint",
                               true,          Geometry::kNone,
                               false,         true};
  static const FieldInfo kLeft{
      "leftFrameGuid",
      "first part joined",
      "left_frame_guid",
      "",
      L::NonEmpty(),
      "guid of the first part joined (a frame or sensor module)",
      true,
      Geometry::kNone,
      false,
      true};
  static const FieldInfo kRight{"rightFrameGuid",
                                "second part joined",
                                "right_frame_guid",
                                "",
                                L::NonEmpty(),
                                "guid of the second part joined",
                                true,
                                Geometry::kNone,
                                false,
                                true};
  static const FieldInfo kType{
      "type",
      "joint type",
      "type",
      "",
      L::Any(),
      "Hinge (motorised, turns about the module axis) or Lock (rigid)",
      true};
  static const FieldInfo kLower{
      "lowerRangeLimit", "lowest angle",       "lower_range_limit", "rad",
      L::Any(),          "Hinge: lowest angle"};
  static const FieldInfo kUpper{
      "upperRangeLimit", "highest angle",       "upper_range_limit", "rad",
      L::Any(),          "Hinge: highest angle"};
  static const FieldInfo kKp{
      "Kp",
      "gain Kp",
      "kp",
      "1/s",
      L::NonNegative(),
      "Hinge: servo gain, speed = Kp * (target - angle)"};
  static const FieldInfo kMaxVel{
      "max_vel",
      "top speed",
      "max_vel",
      "rad/s",
      L::NonNegative(),
      "Hinge: speed limit of the servo (positive; locks ignore it)"};
  static const FieldInfo kVelocityGain{
      "velocityGain",
      "velocity gain",
      "velocity_gain",
      "N m s/rad",
      L::Positive(),
      "Hinge: torque per rad/s of speed error in the servo's velocity loop"};
  static const FieldInfo kMaxTorque{
      "maxTorque",   "stall torque",
      "max_torque",  "N m",
      L::Positive(), "Hinge: stall torque, the most the servo can apply"};
  static const FieldInfo kBreakForce{
      "breakForce",     "breaking force",
      "break_force",    "N",
      L::NonNegative(), "Lock: force at which it breaks; 0 never breaks"};
  static const FieldInfo kServo = [] {
    FieldInfo f{"servo",
                "driven by a servo",
                "servo",
                "",
                L::Any(),
                "Loose hinge: a servo (Kp, max_vel, velocityGain, maxTorque) "
                "drives it to the targets sent on COMMAND_loose; off, it "
                "turns freely. A module's hinge always has one"};
    f.omit_when = "false";
    return f;
  }();
  v.Field(kGuid, j.guid);
  v.Field(kLeft, j.left_frame_guid);
  v.Field(kRight, j.right_frame_guid);
  v.Field(kType, j.type);
  v.Field(kLower, j.lower_range_limit);
  v.Field(kUpper, j.upper_range_limit);
  // Before the gains it switches on, as the inspector lists them.
  v.Field(kServo, j.servo);
  v.Field(kKp, j.kp);
  v.Field(kMaxVel, j.max_vel);
  v.Field(kVelocityGain, j.velocity_gain);
  v.Field(kMaxTorque, j.max_torque);
  v.Field(kBreakForce, j.break_force);
}

template <typename V>
void Describe(V& v, Module& m) {
  static const FieldInfo kNr{
      "mod_Nr",
      "module number",
      "mod_nr",
      "",
      L::Any(),
      "Module number, unique in its robot; sensor modules refer to it",
      true};
  static const FieldInfo kPosition{
      "position",      "hinge position",        "position", "m",
      L::Coordinate(), "Position of the hinge", false,      G::kLengthVector};
  static const FieldInfo kAxis{
      "axis", "bends (axis)", "axis",
      "",     L::Any(),       "Pitch (bends up/down) or Yaw (bends left/right)",
      true};
  static const ChildInfo kFrames{"frames", "Frame", "frames",
                                 "The two rigid bodies", true};
  static const ChildInfo kJoint{"joint", "", "joint",
                                "The hinge between the two frames", true};
  v.Field(kNr, m.mod_nr);
  v.Field(kPosition, m.position);
  v.Field(kAxis, m.axis);
  static const FieldInfo kWheels{
      "passiveWheels",
      "passive wheels",
      "passive_wheels",
      "",
      L::Any(),
      "Passive wheels on both frames: they roll along the chain and grip "
      "across it",
      false,
      G::kNone,
      false,
      false,
      "false"};
  v.Array(kFrames, m.frames);
  v.Child(kJoint, m.joint);
  v.Field(kWheels, m.passive_wheels);
}

template <typename V>
void Describe(V& v, ForceSensor& s) {
  static const FieldInfo kGuid{
      "guid",
      "id",
      "guid",
      "",
      L::Any(),
      "Id the plate's lock may name (optional; nothing else refers to it)",
      false,
      Geometry::kNone,
      false,
      true};
  static const FieldInfo kForce{
      "forceValue",  "force reading",
      "force_value", "N",
      L::Any(),      "Last reading the original saved; not an input",
      false,         Geometry::kNone,
      false,         true};
  static const FieldInfo kFace{"sensorPosition",
                               "face",
                               "sensor_position",
                               "",
                               L::Range(0, 3, kForcePlateFaceList),
                               "Face of the sensor module the plate is on"};
  static const FieldInfo kPosition{"position",      "position",
                                   "position",      "m",
                                   L::Coordinate(), "Position of the plate",
                                   false,           G::kLengthVector};
  static const FieldInfo kRotation{
      "rotation",   "Euler angles as stored",
      "rotation",   "",
      L::NonZero(), "Orientation of the plate as a quaternion",
      false,        G::kQuaternion};
  static const FieldInfo kMaterial{"materialName",  "material",
                                   "material_name", "",
                                   L::Any(),        "Material of the plate"};
  static const FieldInfo kMass{"mass", "mass",    "mass",
                               "kg",   L::Mass(), "Mass of the plate"};
  static const FieldInfo kSize{"size",    "size",
                               "size",    "m",
                               L::Size(), "Plate extents; z is its thickness",
                               false,     G::kLengthVector};
  v.Field(kGuid, s.guid);
  v.Field(kForce, s.force_value);
  v.Field(kFace, s.sensor_position);
  v.Field(kPosition, s.position);
  v.Field(kRotation, s.rotation);
  v.Field(kMaterial, s.material_name);
  v.Field(kMass, s.mass);
  v.Field(kSize, s.size);
}

template <typename V>
void Describe(V& v, DistanceSensor& s) {
  static const FieldInfo kGuid{
      "guid",
      "id",
      "guid",
      "",
      L::Any(),
      "Id the sensor's lock may name (optional; nothing else refers to it)",
      false,
      Geometry::kNone,
      false,
      true};
  static const FieldInfo kFace{"sensorPosition",
                               "face",
                               "sensor_position",
                               "",
                               L::Range(0, 5, kSensorFaceList),
                               "Face of the sensor module the ray starts from"};
  static const FieldInfo kMass{"mass", "mass",    "mass",
                               "kg",   L::Mass(), "Mass of the sensor"};
  static const FieldInfo kSize{"size",    "size",
                               "size",    "m",
                               L::Size(), "Extents of the sensor body",
                               false,     G::kLengthVector};
  static const FieldInfo kRange{"max_rayDistance",
                                "max ray distance",
                                "max_ray_distance",
                                "m",
                                L::Size(),
                                "Reading when nothing is hit within range",
                                false,
                                G::kLength};
  static const FieldInfo kDirection{
      "ray_Direction", "ray direction",
      "ray_direction", "",
      L::NonZero(),    "Ray direction in the sensor module's frame",
      false,           G::kDirection};
  static const FieldInfo kResolution{
      "ray_Resolution",
      "ray resolution",
      "ray_resolution",
      "m",
      L::Size(),
      "Sampling step along the ray in the original; MuJoCo's ray is exact, "
      "so it does not change readings",
      false,
      G::kLength};
  v.Field(kGuid, s.guid);
  v.Field(kFace, s.sensor_position);
  DescribePose(v, s.position, s.rotation, s.quat_rotation);
  v.Field(kMass, s.mass);
  v.Field(kSize, s.size);
  v.Field(kRange, s.max_ray_distance);
  v.Field(kDirection, s.ray_direction);
  v.Field(kResolution, s.ray_resolution);
}

template <typename V>
void Describe(V& v, Imu& s) {
  static const FieldInfo kGuid{
      "guid",   "id",
      "guid",   "",
      L::Any(), "Id of the IMU (optional; nothing refers to it)",
      false,    Geometry::kNone,
      false,    true};
  static const FieldInfo kAccelNoise{
      "accelNoise",
      "accelerometer noise",
      "accel_noise",
      "m/s^2",
      L::NonNegative(),
      "Standard deviation of the accelerometer's white noise; 0: none"};
  static const FieldInfo kGyroNoise{
      "gyroNoise",
      "gyroscope noise",
      "gyro_noise",
      "rad/s",
      L::NonNegative(),
      "Standard deviation of the gyroscope's white noise; 0: none"};
  static const FieldInfo kAccelBias{"accelBias",
                                    "accelerometer bias",
                                    "accel_bias",
                                    "m/s^2",
                                    L::Any(),
                                    "Constant offset of every accelerometer "
                                    "reading, in the module's frame",
                                    false,
                                    G::kDirection};
  // An angular rate is an axial vector: a change of handedness flips it
  // too, so it is left alone rather than mirrored wrongly.
  static const FieldInfo kGyroBias{
      "gyroBias",
      "gyroscope bias",
      "gyro_bias",
      "rad/s",
      L::Any(),
      "Constant offset of every gyroscope reading, in the module's frame"};
  static const FieldInfo kSeed{
      "seed",   "noise seed",
      "seed",   "",
      L::Any(), "Seed of the noise: the same seed gives the same readings"};
  v.Field(kGuid, s.guid);
  v.Field(kAccelNoise, s.accel_noise);
  v.Field(kGyroNoise, s.gyro_noise);
  v.Field(kAccelBias, s.accel_bias);
  v.Field(kGyroBias, s.gyro_bias);
  v.Field(kSeed, s.seed);
}

template <typename V>
void Describe(V& v, Camera& s) {
  static const FieldInfo kGuid{
      "guid",   "id",
      "guid",   "",
      L::Any(), "Id of the camera (optional; nothing refers to it)",
      false,    Geometry::kNone,
      false,    true};
  static const FieldInfo kFace{"sensorPosition",
                               "face",
                               "sensor_position",
                               "",
                               L::Range(0, 5, kSensorFaceList),
                               "Face of its sensor module (or of the box "
                               "around its scene object) the camera looks out "
                               "of, along the face's normal"};
  static const FieldInfo kFovy{
      "fovy",           "vertical field of view",
      "fovy",           "deg",
      L::Range(1, 170), "Angle the picture spans from bottom to top"};
  static const FieldInfo kWidth{
      "width",        "width", "width", "px", L::Range(16, kMaxCameraWidth),
      "Picture width"};
  static const FieldInfo kHeight{
      "height",        "height", "height", "px", L::Range(16, kMaxCameraHeight),
      "Picture height"};
  static const FieldInfo kRate{
      "rate",
      "frame rate",
      "rate",
      "Hz",
      L::Positive().Within(kMaxCameraRate),
      "Pictures per simulated second (at most one per published state)"};
  static const FieldInfo kNear{"near",      "near clip",
                               "near_clip", "m",
                               L::Size(),   "Nothing closer than this is drawn",
                               false,       G::kLength};
  static const FieldInfo kFar{"far",      "far clip",
                              "far_clip", "m",
                              L::Size(),  "Nothing farther than this is drawn",
                              false,      G::kLength};
  static const FieldInfo kTilt{
      "tilt",
      "tilt",
      "tilt",
      "deg",
      L::Range(-89, 89),
      "Turn of the view about its horizontal axis; "
      "positive looks down (for a side face: toward the "
      "module's bottom)"};
  static const FieldInfo kNoise{
      "noise",
      "pixel noise",
      "noise",
      "",
      L::Range(0, 255),
      "Standard deviation of each pixel's white noise in grey levels "
      "(0..255); 0: none"};
  static const FieldInfo kSeed{
      "seed",   "noise seed",
      "seed",   "",
      L::Any(), "Seed of the noise: the same seed gives the same pictures"};
  v.Field(kGuid, s.guid);
  v.Field(kFace, s.sensor_position);
  v.Field(kFovy, s.fovy);
  v.Field(kWidth, s.width);
  v.Field(kHeight, s.height);
  v.Field(kRate, s.rate);
  v.Field(kNear, s.near_clip);
  v.Field(kFar, s.far_clip);
  v.Field(kTilt, s.tilt);
  v.Field(kNoise, s.noise);
  v.Field(kSeed, s.seed);
}

template <typename V>
void Describe(V& v, SensorModule& s) {
  static const FieldInfo kGuid{"guid",        "id",
                               "guid",        "",
                               L::NonEmpty(), "Unique id of the sensor module",
                               true,          Geometry::kNone,
                               false,         true};
  static const FieldInfo kLeft{
      "leftMod_Nr",   "left neighbour module",
      "left_mod_nr",  "",
      L::AtLeast(-1), "mod_Nr of the module on one side; -1: chain end",
      false,          Geometry::kNone,
      false,          true};
  static const FieldInfo kRight{
      "rightMod_Nr",  "right neighbour module",
      "right_mod_nr", "",
      L::AtLeast(-1), "mod_Nr of the module on the other side; -1: chain end",
      false,          Geometry::kNone,
      false,          true};
  static const ChildInfo kForce{"forceSensor", "", "force_sensor",
                                "At most one force plate"};
  static const ChildInfo kForceLock = [] {
    ChildInfo c{"forceSensorLock", "", "force_sensor_lock",
                "Lock of the plate (a placeholder in the original's files)"};
    c.locks = true;
    return c;
  }();
  static const FieldInfo kForceLockPosition{
      "forceLockPosition",
      "force plate lock position",
      "force_lock_position",
      "m",
      L::Coordinate(),
      "Where the original placed the plate's lock",
      false,
      G::kLengthVector};
  static const ChildInfo kDistance = [] {
    ChildInfo c = Wrapper("distanceSensors", "DistanceSensor",
                          "distance_sensors", "Up to six distance sensors");
    c.max_items = 6;
    return c;
  }();
  static const FieldInfo kDistanceLockPosition{
      "distanceLockPosition",
      "distance sensor lock position",
      "distance_lock_position",
      "m",
      L::Coordinate(),
      "Where the original placed the distance sensors' locks",
      false,
      G::kLengthVector};
  static const ChildInfo kDistanceLocks = [] {
    ChildInfo c =
        Wrapper("distanceSensorLocks", "Joint", "distance_sensor_locks",
                "Locks of the distance sensors (placeholders in the "
                "original's files)");
    c.locks = true;
    return c;
  }();
  static const ChildInfo kImu{
      "imu", "", "imu",
      "At most one IMU (accelerometer and gyroscope) at the box's centre"};
  static const ChildInfo kCameras = [] {
    ChildInfo c = Wrapper("cameras", "Camera", "cameras",
                          "Up to six cameras, one per face", false);
    c.max_items = 6;
    c.omit_when_empty = true;
    return c;
  }();
  static const FieldInfo kSize{"size", "size",          "size",
                               "m",    L::Size(),       "Extents of the box",
                               false,  G::kLengthVector};
  static const FieldInfo kMass{"mass", "mass",    "mass",
                               "kg",   L::Mass(), "Mass of the box"};
  static const FieldInfo kMaterial{"materialName",  "material",
                                   "material_name", "",
                                   L::Any(),        "Material of the box"};
  static const FieldInfo kPosition{
      "position",      "centre position",        "position", "m",
      L::Coordinate(), "Position of the centre", false,      G::kLengthVector};
  static const FieldInfo kRotation{
      "rotation", "Euler angles as stored",
      "rotation", "deg",
      L::Any(),   "Euler angles as the original stored them",
      false,      G::kEuler};
  static const FieldInfo kQuat{"quatRotation",  "orientation",
                               "quat_rotation", "",
                               L::NonZero(),    "Orientation as a quaternion",
                               false,           G::kQuaternion};
  v.Field(kGuid, s.guid);
  v.Field(kLeft, s.left_mod_nr);
  v.Field(kRight, s.right_mod_nr);
  v.Optional(kForce, s.force_sensor);
  v.Optional(kForceLock, s.force_sensor_lock);
  v.Field(kForceLockPosition, s.force_lock_position);
  v.List(kDistance, s.distance_sensors);
  v.Field(kDistanceLockPosition, s.distance_lock_position);
  v.List(kDistanceLocks, s.distance_sensor_locks);
  v.Field(kPosition, s.position);
  v.Field(kRotation, s.rotation);
  v.Field(kSize, s.size);
  v.Field(kQuat, s.quat_rotation);
  v.Field(kMass, s.mass);
  v.Field(kMaterial, s.material_name);
  v.Optional(kImu, s.imu);
  v.List(kCameras, s.cameras);
}

template <typename V>
void Describe(V& v, Robot& r) {
  static const FieldInfo kName{
      "name",
      "robot name",
      "name",
      "",
      L::Any(),
      "Unique robot name (letters, digits, _ - .); used in LCM channels; "
      "robot<i> when left out"};
  static const ChildInfo kModules = [] {
    ChildInfo c =
        Wrapper("modules", "Module", "modules", "The modules of the chain");
    c.max_items = kMaxModules;
    c.max_items_why = kMaxModulesWhy;
    return c;
  }();
  static const ChildInfo kSensorModules = [] {
    ChildInfo c = Wrapper("sensorModules", "SensorModule", "sensor_modules",
                          "Sensor modules between the modules");
    c.max_items = kMaxModules;
    c.max_items_why = kMaxModulesWhy;
    return c;
  }();
  static const ChildInfo kLocks = [] {
    ChildInfo c = Wrapper("locks", "Joint", "locks",
                          "Rigid joints between consecutive parts");
    c.locks = true;
    return c;
  }();
  v.Field(kName, r.name);
  v.List(kModules, r.modules);
  v.List(kSensorModules, r.sensor_modules);
  v.List(kLocks, r.locks);
}

template <typename V>
void Describe(V& v, Scene& s) {
  static const FieldInfo kGuid{"guid",   "terrain id",
                               "guid",   "",
                               L::Any(), "Id of the terrain (optional)"};
  static const FieldInfo kImage{
      "height_Image",
      "height image",
      "height_image",
      "",
      L::Any(),
      "Grey-scale height image: a file path or base64 image bytes; empty: "
      "a flat ground plane"};
  static const FieldInfo kPosition{"position",
                                   "position",
                                   "position",
                                   "m",
                                   L::Coordinate(),
                                   "Corner of the terrain (or the plane's "
                                   "height)",
                                   false,
                                   G::kLengthVector};
  static const FieldInfo kMaterial{"materialName",  "material",
                                   "material_name", "",
                                   L::Any(),        "Material of the ground"};
  static const FieldInfo kHeight{
      "height",    "height of the brightest pixel", "height", "m",
      L::Length(), "Height of the brightest pixel", false,    G::kLength};
  static const FieldInfo kPixel{"metersPerPixel",
                                "metres per pixel",
                                "meters_per_pixel",
                                "m",
                                L::Size(),
                                "Horizontal extent of one pixel",
                                false,
                                G::kLength};
  static const ChildInfo kVertices{
      "vertices", "", "",
      "The original's optional mesh terrain; read only when empty"};
  static const ChildInfo kTriangles{
      "triangles", "", "",
      "The original's optional mesh terrain; read only when empty"};
  v.Field(kGuid, s.guid);
  v.Field(kImage, s.height_image);
  v.Field(kPosition, s.position);
  v.Field(kMaterial, s.material_name);
  v.Field(kHeight, s.height);
  v.Field(kPixel, s.meters_per_pixel);
  v.Unsupported(kVertices);
  v.Unsupported(kTriangles);
}

template <typename V>
void Describe(V& v, SceneObject& o) {
  static const FieldInfo kGuid{"guid", "name",        "guid",
                               "",     L::NonEmpty(), "Unique id of the object",
                               true};
  static const FieldInfo kSize{
      "size",
      "size",
      "size",
      "m",
      L::Size(),
      "Box: extents; Sphere: x is the diameter; Cylinder/Capsule: x "
      "diameter, z length",
      false,
      G::kLengthVector};
  static const FieldInfo kMaterial{"materialName",  "material",
                                   "material_name", "",
                                   L::Any(),        "Material of the object"};
  static const FieldInfo kShape{"shape",  "solid shape",
                                "shape",  "",
                                L::Any(), "Box, Sphere, Cylinder or Capsule",
                                true};
  // A static object is welded to the world: its mass moves nothing, so
  // the studio does not offer it (REQ-1.4.5); files keep it.
  static const FieldInfo kMass{"mass",
                               "mass",
                               "mass",
                               "kg",
                               L::NonNegative().Within(kMaxMass),
                               "Mass; positive unless the object is static",
                               false,
                               G::kNone,
                               false,
                               false,
                               nullptr,
                               "!isStatic"};
  static const FieldInfo kStatic{
      "isStatic", "fixed in place", "is_static",
      "",         L::Any(),         "Fixed to the world where it is placed"};
  // A camera sits on a face of the box around the object (a sphere's,
  // cylinder's or capsule's touches it there), like a sensor module's: one
  // convention for both, and the studio's face picker serves both.
  static const ChildInfo kCameras = [] {
    ChildInfo c = Wrapper("cameras", "Camera", "cameras",
                          "Up to six cameras, one per face of the box "
                          "around the object; on a static object, a fixed "
                          "view of the world",
                          false);
    c.max_items = 6;
    c.omit_when_empty = true;
    return c;
  }();
  v.Field(kGuid, o.guid);
  v.Field(kSize, o.size);
  DescribePose(v, o.position, o.rotation, o.quat_rotation);
  v.Field(kMaterial, o.material_name);
  v.Field(kShape, o.shape);
  v.Field(kMass, o.mass);
  v.Field(kStatic, o.is_static);
  v.List(kCameras, o.cameras);
}

template <typename V>
void Describe(V& v, ContactFriction& f) {
  static const FieldInfo kM1{"material1",   "first material",
                             "material1",   "",
                             L::NonEmpty(), "First material of the pair",
                             true};
  static const FieldInfo kM2{
      "material2", "second material", "material2",
      "",          L::NonEmpty(),     "Second material (order does not matter)",
      true};
  static const FieldInfo kRestitution{
      "restitution",  "bounciness (restitution)",
      "restitution",  "",
      L::Range(0, 1), "Bounce: 0 none (critically damped) .. 1 elastic"};
  static const FieldInfo kFriction{"friction",
                                   "friction coefficient",
                                   "friction",
                                   "",
                                   L::NonNegative(),
                                   "Sliding friction coefficient",
                                   false,
                                   G::kNone,
                                   false,
                                   false,
                                   nullptr,
                                   "!directional"};
  // Diamond's is about 1.2e12 Pa.
  static const FieldInfo kYoung{"youngsModulus",
                                "Young's modulus",
                                "youngs_modulus",
                                "Pa",
                                L::Positive().Within(1e13),
                                "Stiffness of the contact (docs/physics.md)"};
  v.Field(kM1, f.material1);
  v.Field(kM2, f.material2);
  v.Field(kRestitution, f.restitution);
  // A friction coefficient above 10 is no surface pair there is (rubber on
  // glass reaches about 4); spin and rolling friction are lengths, at most
  // a contact patch's size.
  static const FieldInfo kDirectional{
      "directional",
      "friction by direction",
      "directional",
      "",
      L::Any(),
      "Friction by direction in material1's part frame (the fields below) "
      "instead of friction",
      false,
      G::kNone,
      false,
      false,
      "false"};
  static const FieldInfo kForward{
      "forwardFriction",
      "forward friction",
      "forward_friction",
      "",
      L::NonNegative().Within(10),
      "Directional: sliding friction along the part's +x (forward)",
      false,
      G::kNone,
      false,
      false,
      "0.5",
      "directional"};
  static const FieldInfo kBackward{
      "backwardFriction",
      "backward friction",
      "backward_friction",
      "",
      L::NonNegative().Within(10),
      "Directional: sliding friction along the part's -x (backward)",
      false,
      G::kNone,
      false,
      false,
      "0.5",
      "directional"};
  static const FieldInfo kLateral{
      "lateralFriction",
      "sideways friction",
      "lateral_friction",
      "",
      L::NonNegative().Within(10),
      "Directional: sliding friction across the part's x axis",
      false,
      G::kNone,
      false,
      false,
      "0.5",
      "directional"};
  static const FieldInfo kTorsional{
      "torsionalFriction",
      "torsional friction",
      "torsional_friction",
      "m",
      L::Length().Within(1),
      "Directional: spin friction about the contact normal; 0 none",
      false,
      G::kNone,
      false,
      false,
      "0",
      "directional"};
  static const FieldInfo kRolling{"rollingFriction",
                                  "rolling friction",
                                  "rolling_friction",
                                  "m",
                                  L::Length().Within(1),
                                  "Directional: rolling friction; 0 none",
                                  false,
                                  G::kNone,
                                  false,
                                  false,
                                  "0",
                                  "directional"};
  v.Field(kFriction, f.friction);
  v.Field(kYoung, f.youngs_modulus);
  v.Field(kDirectional, f.directional);
  v.Field(kForward, f.forward_friction);
  v.Field(kBackward, f.backward_friction);
  v.Field(kLateral, f.lateral_friction);
  v.Field(kTorsional, f.torsional_friction);
  v.Field(kRolling, f.rolling_friction);
}

template <typename V>
void Describe(V& v, FluidRegion& r) {
  static const FieldInfo kGuid{"guid", "name",   "guid",
                               "",     L::Any(), "Id of the region (optional)"};
  static const FieldInfo kKind{
      "kind",
      "water or air",
      "kind",
      "",
      L::Any(),
      "Water (buoyancy and drag) or Air (drag); sets density and viscosity "
      "defaults",
      true};
  static const FieldInfo kPosition{
      "position",      "position",          "position", "m",
      L::Coordinate(), "Centre of the box", false,      G::kLengthVector};
  static const FieldInfo kSize{"size", "size",          "size",
                               "m",    L::Size(),       "Extents of the box",
                               false,  G::kLengthVector};
  static const FieldInfo kDensity{"density",     "density",
                                  "density",     "kg/m^3",
                                  L::Positive(), "Density of the fluid"};
  static const FieldInfo kViscosity{
      "viscosity", "viscosity",      "viscosity",
      "Pa s",      L::NonNegative(), "Dynamic viscosity of the fluid"};
  static const FieldInfo kVelocity{
      "velocity", "flow velocity",         "velocity", "m/s",
      L::Any(),   "Flow or wind velocity", false,      G::kLengthVector};
  v.Field(kGuid, r.guid);
  v.Field(kKind, r.kind);
  v.Field(kPosition, r.position);
  v.Field(kSize, r.size);
  v.Field(kDensity, r.density);
  v.Field(kViscosity, r.viscosity);
  v.Field(kVelocity, r.velocity);
}

template <typename V>
void Describe(V& v, SimulationSettings& s) {
  static const FieldInfo kTimestep{"timestep",
                                   "time step",
                                   "timestep",
                                   "s",
                                   L::Range(kMinTimestep, kMaxTimestep),
                                   "Physics step"};
  static const FieldInfo kGravity{
      "gravity", "gravity",
      "gravity", "m/s^2",
      L::Any(),  "Gravity; a unit scale (convert --scale) leaves it alone",
      false,     G::kDirection};
  v.Field(kTimestep, s.timestep);
  v.Field(kGravity, s.gravity);
}

template <typename V>
void Describe(V& v, RunSettings& r) {
  static const FieldInfo kClock{
      "clock",
      "clock mode",
      "clock",
      "",
      L::Any(),
      "How simulated time runs: realtime, fast or lockstep (mrsim-sim "
      "--clock)"};
  static const FieldInfo kRate{
      "rate",
      "publish rate",
      "rate",
      "Hz",
      L::Positive().Within(kMaxControlRate),
      "State publication rate = control rate (mrsim-sim --rate)"};
  static const FieldInfo kSpeed{
      "speed",
      "speed (times real time)",
      "speed",
      "",
      L::Positive().Within(kMaxRealtimeFactor),
      "Real-time factor of the realtime clock (mrsim-sim --speed)"};
  static const FieldInfo kController{
      "controller",
      "controller kind",
      "controller",
      "",
      L::Any(),
      "Who drives the robots: gait (mrsim-gait), lua (mrsim-lua running "
      "luaScript) or external (lockstep, waiting for externalName)"};
  static const FieldInfo kGait{
      "gait",
      "starting gait",
      "gait",
      "",
      L::TextUpTo(kMaxRunNameBytes, true),
      "The gait each robot starts with (controller gait)"};
  static const FieldInfo kTunedGait{
      "tunedGait",
      "tuned gait",
      "tuned_gait",
      "",
      L::TextUpTo(kMaxTunedGaitBytes),
      "The gait as tuned in the studio's Run panel, a gait file's text "
      "(docs/gait.md); replaces the starting gait (controller gait)",
      false,
      G::kNone,
      false,
      false,
      ""};
  static const FieldInfo kLua{"luaScript",
                              "Lua script",
                              "lua_script",
                              "",
                              L::TextUpTo(kMaxLuaScriptBytes),
                              "The Lua controller's source (controller lua)",
                              false,
                              G::kNone,
                              false,
                              false,
                              ""};
  static const FieldInfo kExternal{
      "externalName",
      "external controller name",
      "external_name",
      "",
      L::TextUpTo(kMaxRunNameBytes),
      "The sender the simulator waits for (controller external)",
      false,
      G::kNone,
      false,
      false,
      ""};
  v.Field(kClock, r.clock);
  v.Field(kRate, r.rate);
  v.Field(kSpeed, r.speed);
  v.Field(kController, r.controller);
  v.Field(kGait, r.gait);
  v.Field(kTunedGait, r.tuned_gait);
  v.Field(kLua, r.lua_script);
  v.Field(kExternal, r.external_name);
}

// A text field of <optimization> left out of the file when empty.
inline FieldInfo OptionalText(const char* xml, const char* label,
                              const char* member, size_t max_bytes,
                              const char* help) {
  FieldInfo f{xml, label, member, "", L::TextUpTo(max_bytes), help};
  f.omit_when = "";
  return f;
}

// The reality gap's fields of <optimization>, in RealityGap's order: each
// between 0 and the maximum RealityGap::Validate allows, left out of the
// file at RealityGap::Typical()'s value (both from reality_gap_limits.h).
// One table for every Describe instantiation, built once.
inline const std::vector<FieldInfo>& RealityGapFields() {
  struct Row {
    const char* xml;
    const char* label;
    const char* member;
    const char* unit;
    double max;
    double typical;
    const char* help;
  };
  static const std::vector<Row> kRows = {
      {"gapSensorNoise", "sensor noise", "gap_sensor_noise", "",
       kGapMaxSensorNoise, kGapTypicalSensorNoise,
       "Reality gap, per step: sd of the noise on force and distance "
       "readings, as a share of the reading"},
      {"gapSensorBias", "sensor bias", "gap_sensor_bias", "", kGapMaxSensorBias,
       kGapTypicalSensorBias,
       "Reality gap, per step: each force or distance sensor reads up to "
       "this share high or low for the whole episode"},
      {"gapJointNoise", "joint angle noise", "gap_joint_noise", "rad",
       kGapMaxJointNoise, kGapTypicalJointNoise,
       "Reality gap, per step: sd of the noise on joint angle readings"},
      {"gapMotorNoise", "motor noise", "gap_motor_noise", "rad/s",
       kGapMaxMotorNoise, kGapTypicalMotorNoise,
       "Reality gap, per step: sd of the noise added to each servo's speed "
       "command"},
      {"gapLatency", "servo latency", "gap_latency", "s", kGapMaxLatency,
       kGapTypicalLatency,
       "Reality gap, per step: the servo acts on the targets of this long "
       "ago"},
      {"gapBacklash", "backlash", "gap_backlash", "rad", kGapMaxBacklash,
       kGapTypicalBacklash,
       "Reality gap, per step: dead band of the servo's position loop"},
      {"gapMaxAccel", "servo acceleration limit", "gap_max_accel", "rad/s^2",
       kGapMaxMaxAccel, kGapTypicalMaxAccel,
       "Reality gap, per step: the speed command changes by at most this per "
       "second (0: no limit)"},
      {"gapFrictionRange", "friction variation", "gap_friction_range", "",
       kGapMaxRange, kGapTypicalFrictionRange,
       "Reality gap, per episode: every contact friction x U(1-r, 1+r)"},
      {"gapMassRange", "mass variation", "gap_mass_range", "", kGapMaxRange,
       kGapTypicalMassRange,
       "Reality gap, per episode: every frame, sensor module, plate and "
       "object mass x U(1-r, 1+r)"},
      {"gapGainRange", "servo gain variation", "gap_gain_range", "",
       kGapMaxRange, kGapTypicalGainRange,
       "Reality gap, per episode: each hinge's Kp, velocityGain and "
       "maxTorque x U(1-r, 1+r)"},
      {"gapTerrainRange", "terrain height variation", "gap_terrain_range", "",
       kGapMaxRange, kGapTypicalTerrainRange,
       "Reality gap, per episode: the height field's height x U(1-r, 1+r)"},
  };
  // The default's text, as the writer would write it: kept alive here
  // because FieldInfo::omit_when points into it.
  static const std::vector<std::string> kTypicalText = [] {
    std::vector<std::string> texts;
    for (const Row& r : kRows) texts.push_back(FormatNumber(r.typical));
    return texts;
  }();
  static const std::vector<FieldInfo> kFields = [] {
    std::vector<FieldInfo> fields;
    for (size_t i = 0; i < kRows.size(); ++i) {
      const Row& r = kRows[i];
      FieldInfo f{r.xml, r.label, r.member, r.unit, L::Range(0, r.max), r.help};
      f.omit_when = kTypicalText[i].c_str();
      fields.push_back(f);
    }
    return fields;
  }();
  return kFields;
}

template <typename V>
void Describe(V& v, OptimizationSettings& o) {
  static const FieldInfo kAlgorithm{
      "algorithm",
      "search algorithm",
      "algorithm",
      "",
      L::TextUpTo(kMaxOptimizationWordBytes, true),
      "The search algorithm: ga, sa, pso, cmaes or random (mrsim-opt "
      "--algorithm)"};
  static const FieldInfo kGenerations{
      "generations",    "number of generations",
      "generations",    "",
      L::Range(1, 1e8), "Generations to run (mrsim-opt --generations)"};
  static const FieldInfo kPopulation{
      "population",     "individuals per generation",
      "population",     "",
      L::Range(1, 1e6), "Individuals per generation (mrsim-opt --population)"};
  static const FieldInfo kSeed{
      "seed",           "random seed",
      "seed",           "",
      L::NonNegative(), "Seed of the run's random engine (mrsim-opt --seed)"};
  static const FieldInfo kEpisode{
      "episode",
      "episode length",
      "episode",
      "s",
      L::Positive().Within(1e6),
      "Simulated time each individual runs (mrsim-opt --episode)"};
  static const FieldInfo kController{
      "controller",
      "genes drive",
      "controller",
      "",
      L::TextUpTo(kMaxOptimizationWordBytes, true),
      "What the genes drive: gait, cpg, lua (the <run> element's script), "
      "lua:FILE or mlp:H (mrsim-opt --controller)"};
  static const FieldInfo kGenes = OptionalText(
      "genes", "built-in gene set", "genes", kMaxOptimizationWordBytes,
      "The gait's genes as a built-in set: sine or cpg (mrsim-opt --genes); "
      "instead of genome");
  static const FieldInfo kGenome = OptionalText(
      "genome", "genes (genome text)", "genome", kMaxGenomeTextBytes,
      "The genes as a genome file's text (docs/optimizer.md; mrsim-opt "
      "--genome); instead of genes");
  static const FieldInfo kTask = OptionalText(
      "task", "task of the suite", "task", kMaxOptimizationWordBytes,
      "A task of the suite optimised instead of this design's world "
      "(mrsim-opt --task; mrsim tasks lists them)");
  static const FieldInfo kBaseGait = OptionalText(
      "baseGait", "base gait", "base_gait", kMaxPathBytes,
      "The gait the genes modify: a preset or a gait file beside the design; "
      "empty: forward, or the task's own (mrsim-opt --gait)");
  static const FieldInfo kDistance{
      "distance",
      "distance scored",
      "distance",
      "",
      L::TextUpTo(kMaxOptimizationWordBytes, true),
      "Distance scored: forward (+x), net (any direction) or up (+z) "
      "(mrsim-opt --distance)"};
  static const FieldInfo kWDistance{
      "wDistance", "weight of distance",         "w_distance", "1/m",
      L::Any(),    "Fitness per metre travelled"};
  static const FieldInfo kWSpeed{"wSpeed", "weight of speed", "w_speed", "s/m",
                                 L::Any(), "Fitness per m/s"};
  static const FieldInfo kWEnergy{"wEnergy",  "weight of energy",
                                  "w_energy", "1/J",
                                  L::Any(),   "Fitness subtracted per joule"};
  static const FieldInfo kWDrift{
      "wDrift",  "weight of drift",
      "w_drift", "1/m",
      L::Any(),  "Fitness subtracted per metre of sideways drift"};
  static const FieldInfo kWFall{
      "wFall",  "weight of falling",
      "w_fall", "",
      L::Any(), "Fitness subtracted per fraction of the episode upside down"};
  static const FieldInfo kRobust{
      "robust",
      "robust episodes",
      "robust",
      "",
      L::Range(0, 1000),
      "K > 0: each genome's fitness over K worlds of the reality gap "
      "(mrsim-opt --robust)"};
  static const FieldInfo kRobustMode{
      "robustMode",
      "robust score",
      "robust_mode",
      "",
      L::TextUpTo(kMaxOptimizationWordBytes, true),
      "mean or worst of the K perturbed episodes (mrsim-opt --robust-mode)"};
  static const FieldInfo kAllowOverlap = [] {
    FieldInfo f{"allowOverlap",
                "allow overlap",
                "allow_overlap",
                "",
                L::Any(),
                "Optimise even when parts overlap at the start (mrsim-opt "
                "--allow-overlap)"};
    f.omit_when = "false";
    return f;
  }();
  static const FieldInfo kSettings = OptionalText(
      "algorithmSettings", "algorithm settings", "algorithm_settings",
      kMaxAlgorithmSettingsBytes,
      "The algorithm's own settings, flag=value words (cmaes-sigma=0.2), "
      "each a flag of mrsim-opt");
  v.Field(kAlgorithm, o.algorithm);
  v.Field(kGenerations, o.generations);
  v.Field(kPopulation, o.population);
  v.Field(kSeed, o.seed);
  v.Field(kEpisode, o.episode);
  v.Field(kController, o.controller);
  v.Field(kGenes, o.genes);
  v.Field(kGenome, o.genome);
  v.Field(kTask, o.task);
  v.Field(kBaseGait, o.base_gait);
  v.Field(kDistance, o.distance);
  v.Field(kWDistance, o.w_distance);
  v.Field(kWSpeed, o.w_speed);
  v.Field(kWEnergy, o.w_energy);
  v.Field(kWDrift, o.w_drift);
  v.Field(kWFall, o.w_fall);
  v.Field(kRobust, o.robust);
  v.Field(kRobustMode, o.robust_mode);
  v.Field(kAllowOverlap, o.allow_overlap);
  v.Field(kSettings, o.algorithm_settings);
  const std::vector<FieldInfo>& gap = RealityGapFields();
  v.Field(gap[0], o.gap_sensor_noise);
  v.Field(gap[1], o.gap_sensor_bias);
  v.Field(gap[2], o.gap_joint_noise);
  v.Field(gap[3], o.gap_motor_noise);
  v.Field(gap[4], o.gap_latency);
  v.Field(gap[5], o.gap_backlash);
  v.Field(gap[6], o.gap_max_accel);
  v.Field(gap[7], o.gap_friction_range);
  v.Field(gap[8], o.gap_mass_range);
  v.Field(gap[9], o.gap_gain_range);
  v.Field(gap[10], o.gap_terrain_range);
}

template <typename V>
void Describe(V& v, Scenario& s) {
  static const ChildInfo kRobot{"robot", "", "robots",
                                "Robots (repeat <robot>)"};
  static const ChildInfo kScene{"scene", "", "scene",
                                "Terrain, or the flat ground"};
  static const ChildInfo kObjects = Wrapper(
      "sceneObjects", "SceneObject", "scene_objects", "Free-standing objects");
  static const ChildInfo kFrictions =
      Wrapper("contactFrictions", "ContactFriction", "contact_frictions",
              "Contact parameters per pair of materials");
  static const ChildInfo kFluids = [] {
    ChildInfo c = Wrapper("fluidRegions", "FluidRegion", "fluid_regions",
                          "Water and air regions", false);
    c.omit_when_empty = true;
    return c;
  }();
  static const ChildInfo kSettings{"settings", "", "settings",
                                   "Timestep and gravity"};
  static const ChildInfo kRun{
      "run", "", "run",
      "How to run it: clock, rate, controller (mrsim-sim FILE uses it)"};
  static const ChildInfo kOptimization{
      "optimization", "", "optimization",
      "How to optimise it: algorithm, budget, fitness, genes (mrsim-opt "
      "FILE uses it)"};
  static const ChildInfo kFrames = [] {
    ChildInfo c = Wrapper("frames", "Frame", "loose_frames",
                          "Frames without a robot", false);
    c.omit_when_empty = true;
    return c;
  }();
  static const ChildInfo kSensorModules = [] {
    ChildInfo c =
        Wrapper("sensorModules", "SensorModule", "loose_sensor_modules",
                "Sensor modules without a robot");
    c.omit_when_empty = true;
    return c;
  }();
  static const ChildInfo kJoints = [] {
    ChildInfo c =
        Wrapper("joints", "Joint", "loose_joints",
                "Joints between loose frames and sensor modules", false);
    c.omit_when_empty = true;
    return c;
  }();
  v.List(kRobot, s.robots);
  v.Child(kScene, s.scene);
  v.List(kObjects, s.scene_objects);
  v.List(kFrictions, s.contact_frictions);
  v.List(kFluids, s.fluid_regions);
  v.Child(kSettings, s.settings);
  v.Optional(kRun, s.run);
  v.Optional(kOptimization, s.optimization);
  v.List(kFrames, s.loose_frames);
  v.List(kSensorModules, s.loose_sensor_modules);
  v.List(kJoints, s.loose_joints);
}

template <typename T>
struct KindOf;
#define MRSIM_PART_KIND_KIND_OF(Kind, Name, Type)      \
  template <>                                          \
  struct KindOf<Type> {                                \
    static constexpr PartKind kValue = PartKind::Kind; \
  };
MRSIM_PART_KINDS(MRSIM_PART_KIND_KIND_OF)
#undef MRSIM_PART_KIND_KIND_OF

// The names of a choice field's values, in enum order.
inline const std::vector<std::string>& ChoiceNames(const Axis*) {
  static const std::vector<std::string> k{"Pitch", "Yaw"};
  return k;
}
inline const std::vector<std::string>& ChoiceNames(const JointType*) {
  static const std::vector<std::string> k{"Hinge", "Lock"};
  return k;
}
inline const std::vector<std::string>& ChoiceNames(const PrimitiveShape*) {
  static const std::vector<std::string> k{"Box", "Sphere", "Cylinder",
                                          "Capsule"};
  return k;
}
inline const std::vector<std::string>& ChoiceNames(const FluidKind*) {
  static const std::vector<std::string> k{"Water", "Air"};
  return k;
}

// The words of the run settings' choices: their enum tables' words, in
// table order, which is enum order.
inline const std::vector<std::string>& ChoiceNames(const ClockMode*) {
  static const std::vector<std::string> k = ClockModes().Names();
  return k;
}
inline const std::vector<std::string>& ChoiceNames(const ControllerKind*) {
  static const std::vector<std::string> k = ControllerKinds().Names();
  return k;
}

// Applies a frame change and/or a unit scale to every field the schema
// marks with a Geometry, in a part and all its children.
struct GeometryMap {
  bool swap_yz = false;  // Unity Y-up <-> Z-up (its own inverse)
  double scale = 1.0;    // multiplies lengths

  template <typename T>
  void Field(const FieldInfo& info, T& value) {
    if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      Eigen::Vector3d& v = value;
      switch (info.geometry) {
        case Geometry::kLengthVector:
          if (swap_yz) std::swap(v[1], v[2]);
          v *= scale;
          break;
        case Geometry::kDirection:
          if (swap_yz) std::swap(v[1], v[2]);
          break;
        case Geometry::kEuler:
          // + 0.0 turns -0 into 0, so converted zeros print as "0".
          if (swap_yz) v = Eigen::Vector3d(-v[0], -v[2], -v[1]) + Zero();
          break;
        default:
          break;
      }
    } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
      if (swap_yz && info.geometry == Geometry::kQuaternion) {
        const double x = value.x(), y = value.y(), z = value.z();
        value.x() = -x + 0.0;
        value.y() = -z + 0.0;
        value.z() = -y + 0.0;
      }
    } else if constexpr (std::is_same_v<T, double>) {
      if (info.geometry == Geometry::kLength) value *= scale;
    }
  }
  template <typename P>
  void Child(const ChildInfo&, P& part) {
    Describe(*this, part);
  }
  static Eigen::Vector3d Zero() { return Eigen::Vector3d::Zero(); }
  template <typename P>
  void Optional(const ChildInfo&, std::optional<P>& part) {
    if (part) Describe(*this, *part);
  }
  template <typename P, size_t N>
  void Array(const ChildInfo&, std::array<P, N>& parts) {
    for (P& p : parts) Describe(*this, p);
  }
  template <typename P>
  void List(const ChildInfo&, std::vector<P>& parts) {
    for (P& p : parts) Describe(*this, p);
  }
  void Unsupported(const ChildInfo&) {}
};

}  // namespace schema
}  // namespace mrsim
