// The one description of every scenario part: for each field its XML name,
// its label in words for the studio, C++ member, type, unit, limits, default
// and help text, and for each part the child parts it holds. Reading, writing
// and validating scenario files, frame and unit conversion, and the studio's
// inspector all walk it (docs/scenario.md, "The schema").
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// How a field's value is stored and written.
enum class FieldType {
  kText,        // std::string
  kNumber,      // double
  kInteger,     // int
  kBool,        // bool, "true"/"false"
  kVector,      // Eigen::Vector3d, <x><y><z>; as text "x y z"
  kQuaternion,  // Eigen::Quaterniond, <x><y><z><w>; as text "x y z w"
  kChoice,      // an enum, written by name (FieldRef::choices())
};
const char* ToString(FieldType type);

// What a field means geometrically: how a frame change (Unity Y-up to
// Z-up) and a unit scale (ScaleLengths) act on it.
enum class Geometry {
  kNone,          // unchanged by both
  kLength,        // scalar length: scaled
  kLengthVector,  // position, size, scale, velocity: y/z swapped, scaled
  kDirection,     // direction or acceleration: y/z swapped, not scaled
  kEuler,         // Euler angles in degrees: (x,y,z) -> (-x,-z,-y)
  kQuaternion,    // rotation: (x,y,z,w) -> (-x,-z,-y,w)
};

// Physical bounds on what a scenario may hold (docs/scenario.md, "Limits").
// A value beyond them is no robot or world the physics can step: 1e308 in
// a position overflowed MuJoCo's arithmetic, so the simulator stood at sim
// time 0 or failed at its first step; the validator refuses it instead,
// naming the field.
inline constexpr double kMaxAnyValue = 1e9;    // every number, any unit
inline constexpr double kMaxCoordinate = 1e4;  // m: each axis of a position
inline constexpr double kMaxLength = 1e4;      // m: sizes, scales, ranges
inline constexpr double kMaxMass = 1e6;        // kg
inline constexpr double kMinTimestep = 1e-6;   // s: shorter never advances
inline constexpr double kMaxTimestep = 1;      // s
// A camera's picture (px): one raw RGB picture of the largest size (900 kB)
// still fits the image message's `max:` (camera_image_t.lcm) and is
// rendered on the CPU in a few milliseconds.
inline constexpr int kMaxCameraWidth = 640;
inline constexpr int kMaxCameraHeight = 480;
inline constexpr double kMaxCameraRate = 120;  // pictures per simulated s
// Parts in one list (modules of a robot, scene objects, ...): the reader
// stops at the first beyond, before building any.
inline constexpr int kMaxListItems = 10000;
// Per robot, sensor modules too. Why not more (docs/physics.md, "Long
// chains and crowds"): MuJoCo 2.2's dense Newton solver makes a chain's
// step grow with about the cube of its joints, and one world holds at
// most 3 000 resting contacts.
inline constexpr int kMaxModules = 1000;
inline constexpr const char* kMaxModulesWhy =
    "a chain's physics step grows with about the cube of its joints (200 "
    "modules take 7.9 ms a step, 1000 would take about a second) and one "
    "world holds at most 3000 resting contacts, about 750 boxes on the "
    "ground; docs/physics.md, 'Long chains and crowds'";

// The values a field accepts. For vectors and quaternions min, max and
// magnitude apply to each component.
struct FieldLimits {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  // |value| <= magnitude: every number has a physical bound, the schema's
  // own for positions, sizes and masses (Within), kMaxAnyValue otherwise.
  double magnitude = kMaxAnyValue;
  bool min_exclusive = false;  // min < value, not min <= value
  bool nonzero = false;        // vector or quaternion: not all zeros
  bool nonempty = false;       // text: not empty
  const char* meaning = "";    // names of an integer range's values
  size_t max_bytes = 0;        // text: at most this long; 0: any

  static FieldLimits Any() { return {}; }
  static FieldLimits Positive() {
    FieldLimits l;
    l.min = 0;
    l.min_exclusive = true;
    return l;
  }
  static FieldLimits NonNegative() {
    FieldLimits l;
    l.min = 0;
    return l;
  }
  static FieldLimits AtLeast(double min) {
    FieldLimits l;
    l.min = min;
    return l;
  }
  static FieldLimits Range(double min, double max, const char* meaning = "") {
    FieldLimits l;
    l.min = min;
    l.max = max;
    l.meaning = meaning;
    return l;
  }
  static FieldLimits NonZero() {
    FieldLimits l;
    l.nonzero = true;
    return l;
  }
  static FieldLimits NonEmpty() {
    FieldLimits l;
    l.nonempty = true;
    return l;
  }
  // Text of at most `max` bytes (`nonempty`: and at least one).
  static FieldLimits TextUpTo(size_t max, bool nonempty = false) {
    FieldLimits l;
    l.max_bytes = max;
    l.nonempty = nonempty;
    return l;
  }
  // The same limits with a physical bound: |value| <= bound.
  FieldLimits Within(double bound) const {
    FieldLimits l = *this;
    l.magnitude = bound;
    return l;
  }
  // Shorthands for the table: a position, a size (positive), a length
  // (>= 0), a mass (positive).
  static FieldLimits Coordinate() { return Any().Within(kMaxCoordinate); }
  static FieldLimits Size() { return Positive().Within(kMaxLength); }
  static FieldLimits Length() { return NonNegative().Within(kMaxLength); }
  static FieldLimits Mass() { return Positive().Within(kMaxMass); }
};

// One field of a part. The type comes from the member it describes.
struct FieldInfo {
  const char* xml;  // element name in the file, e.g. "Kp"
  // In words for a person, without the unit, e.g. "gain Kp": the studio's
  // label (with the unit after it), the XML name going to its tooltip.
  const char* label;
  const char* member;  // C++ member, e.g. "kp"
  const char* unit;    // "m", "kg", "rad", "rad/s", "N m", ... or ""
  FieldLimits limits;
  const char* help;       // one line for tooltips and docs
  bool required = false;  // must appear in a file
  Geometry geometry = Geometry::kNone;
  bool uniform_scalar = false;  // a vector may be written as one number
  // Names or links a robot's parts (guids, joint ends, neighbours) or
  // records a reading: the tools keep it, so the studio shows it without
  // offering to edit it.
  bool kept = false;
  // Not written when its value's text is this (an option most files leave
  // at its default, added after files existed); nullptr: always written.
  const char* omit_when = nullptr;
  // The xml name of a boolean sibling field this one only means something
  // beside: "directional" (used only when it is true) or "!directional"
  // (only when false). The studio hides it otherwise (REQ-1.4.5); files
  // keep it either way. nullptr: always meaningful.
  const char* shown_when = nullptr;
};

// How many of a child part there are.
enum class ChildCount {
  kOne,       // always present in the model (the element may be optional)
  kOptional,  // std::optional
  kArray,     // std::array, exactly N items in a wrapper
  kList,      // std::vector in a wrapper element of `item`s
  kRepeated,  // std::vector of elements repeated in the parent, no wrapper
};

// Every kind of scenario part, once: its enumerator, its element name in
// files, and its model type (scenario.h). The enum, ToString, AllPartKinds,
// the schema's per-kind table (FieldSpecsOf) and the schema document are
// all made from this list, so a kind cannot be added without being
// described (the studio's SelectionKind takes its values from it too).
#define MRSIM_PART_KINDS(X)                               \
  X(kScenario, "Scenario", Scenario)                      \
  X(kRobot, "robot", Robot)                               \
  X(kModule, "Module", Module)                            \
  X(kFrame, "Frame", Frame)                               \
  X(kJoint, "Joint", Joint)                               \
  X(kSensorModule, "SensorModule", SensorModule)          \
  X(kForceSensor, "forceSensor", ForceSensor)             \
  X(kDistanceSensor, "DistanceSensor", DistanceSensor)    \
  X(kImu, "imu", Imu)                                     \
  X(kCamera, "Camera", Camera)                            \
  X(kScene, "scene", Scene)                               \
  X(kSceneObject, "SceneObject", SceneObject)             \
  X(kContactFriction, "ContactFriction", ContactFriction) \
  X(kFluidRegion, "FluidRegion", FluidRegion)             \
  X(kSettings, "settings", SimulationSettings)            \
  X(kRunSettings, "run", RunSettings)                     \
  X(kOptimizationSettings, "optimization", OptimizationSettings)

// What kind of part a child is.
enum class PartKind {
#define MRSIM_PART_KIND_ENUMERATOR(Kind, Name, Type) Kind,
  MRSIM_PART_KINDS(MRSIM_PART_KIND_ENUMERATOR)
#undef MRSIM_PART_KIND_ENUMERATOR
};
// Every part kind, in the enum's order.
const std::vector<PartKind>& AllPartKinds();
// The part's element name in files, e.g. "Frame", "SensorModule".
const char* ToString(PartKind kind);

// A child part (or list of parts) of a part.
struct ChildInfo {
  const char* xml;   // the element (or wrapper) name, e.g. "modules"
  const char* item;  // list items' element name, e.g. "Module"; else ""
  const char* member;
  const char* help;
  bool required = false;          // the element must appear in a file
  int max_items = kMaxListItems;  // lists: at most this many
  // Why the cap is where it is, when a user may reach it: the refusal
  // says it, so a cap never looks arbitrary.
  const char* max_items_why = "";
  bool assembly = false;         // the wrapper carries xmlns="Assembly"
  bool omit_when_empty = false;  // an empty list is not written at all
  bool locks = false;  // joints in a lock list: <type> may be left out
};

// A field's value, the variant of all member types a field can have.
using FieldPtr =
    std::variant<std::string*, double*, int*, bool*, Eigen::Vector3d*,
                 Eigen::Quaterniond*, Axis*, JointType*, PrimitiveShape*,
                 FluidKind*, ClockMode*, ControllerKind*>;

// A value that does not parse or is outside a field's limits. what() is the
// schema's message, e.g. "expected a positive value, got 0".
class FieldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One field of one part in memory: what the inspector edits.
class FieldRef {
 public:
  FieldRef(const FieldInfo& info, FieldPtr value)
      : info_(&info), value_(value) {}

  const FieldInfo& info() const { return *info_; }
  FieldType type() const;
  // kChoice: the names it accepts ("Pitch", "Yaw"); else empty.
  std::vector<std::string> choices() const;
  // The value as text: shortest round-tripping numbers, vectors "x y z",
  // quaternions "x y z w", bools "true"/"false", choices by name.
  std::string GetText() const;
  // Parses `text` as GetText writes it, checks the limits and stores it.
  // Throws FieldError with the schema's message; the value is unchanged
  // on error.
  void SetText(const std::string& text) const;
  // As SetText without the limits, for readers that validate the whole
  // scenario afterwards (ValidateScenario). Throws FieldError.
  void SetTextUnchecked(const std::string& text) const;
  // Empty when the value is within the limits, else the schema's message.
  std::string Check() const;
  const FieldPtr& value() const { return value_; }

 private:
  const FieldInfo* info_;
  FieldPtr value_;
};

// The fields (not child parts) of one part, in file order.
std::vector<FieldRef> FieldsOf(Scenario& part);
std::vector<FieldRef> FieldsOf(Robot& part);
std::vector<FieldRef> FieldsOf(Module& part);
std::vector<FieldRef> FieldsOf(Frame& part);
std::vector<FieldRef> FieldsOf(Joint& part);
std::vector<FieldRef> FieldsOf(SensorModule& part);
std::vector<FieldRef> FieldsOf(ForceSensor& part);
std::vector<FieldRef> FieldsOf(DistanceSensor& part);
std::vector<FieldRef> FieldsOf(Imu& part);
std::vector<FieldRef> FieldsOf(Camera& part);
std::vector<FieldRef> FieldsOf(Scene& part);
std::vector<FieldRef> FieldsOf(SceneObject& part);
std::vector<FieldRef> FieldsOf(ContactFriction& part);
std::vector<FieldRef> FieldsOf(FluidRegion& part);
std::vector<FieldRef> FieldsOf(SimulationSettings& part);
std::vector<FieldRef> FieldsOf(RunSettings& part);
std::vector<FieldRef> FieldsOf(OptimizationSettings& part);

// A field of a kind of part, without an instance: for listings and docs.
struct FieldSpec {
  FieldInfo info;
  FieldType type;
  std::string default_text;  // the value in a default-constructed part
  std::vector<std::string> choices;
};
// A child of a kind of part.
struct ChildSpec {
  ChildInfo info;
  ChildCount count;
  PartKind kind;
};
const std::vector<FieldSpec>& FieldSpecsOf(PartKind kind);
const std::vector<ChildSpec>& ChildSpecsOf(PartKind kind);

// Text <-> value with the schema's messages, for one field type; used by
// FieldRef and the XML reader. ParseNumber accepts what XML and .NET write
// ("1.5", "+2", "1e-3"); FormatNumber gives the shortest text that reads
// back to the same double.
double ParseNumber(const std::string& text);  // throws FieldError
int ParseInteger(const std::string& text);    // throws FieldError
bool ParseBool(const std::string& text);      // throws FieldError
std::string FormatNumber(double value);

// What the reader and the validator say about a list longer than its
// max_items, e.g. "more than 1000 <Module> in <modules> (at most 1000)".
std::string ListLimitMessage(const ChildInfo& info);

}  // namespace mrsim
