// Fields a file may carry that place or change nothing in the simulation
// (REQ-1.4.5): the original's Euler `rotation` beside the quaternion that
// places the part, a sensor module's lock positions and its force plate's
// pose (both follow from the face), a ray's sampling step (rays are cast
// exactly), a hinge's breakForce (only locks break), a lock's servo, a
// passive loose hinge's servo gains and a flat ground's pixels. Files that have
// them still load and keep them; the inspector does not offer them.
#pragma once

#include <string>
#include <vector>

#include "studio/design/schema.h"

namespace mrsim::studio {

// `fields` without those whose xml name is in `inert`.
std::vector<FieldRef> WithoutInert(std::vector<FieldRef> fields,
                                   const std::vector<std::string>& inert);

// Where a joint sits, which decides what of it does something.
enum class JointPlace {
  kModule,     // a module's hinge: Lock is refused there and never breaks
  kRobotLock,  // in Robot::locks: rigid, only its breaking force matters
  kLoose,      // a loose joint: a Hinge (passive unless its `servo` is on)
               // or a Lock, as its type says
};

// The fields of `joint` that do something where it sits: a lock offers its
// breaking force (and shows the two parts it joins), a hinge its limits and
// servo (a loose hinge the servo switch, and its gains while it is on),
// never the other's.
std::vector<FieldRef> JointFields(Joint& joint, JointPlace place);

// The terrain's fields without the height image's pixel height and size
// when it is flat ground (no image): they shape nothing then.
std::vector<FieldRef> TerrainFields(Scene& scene);

// Which components of a scene object's `size` its shape reads, with their
// names: a box all three, a sphere x (its diameter), a cylinder or capsule
// x (diameter) and z (length). The inspector offers those alone.
struct SizeComponent {
  int axis;           // 0 x, 1 y, 2 z
  const char* label;  // "diameter", "length", "x", ...
};
std::vector<SizeComponent> SizeComponents(PrimitiveShape shape);

// `size` with the components `shape` does not read set to the first one it
// reads (a sphere of diameter d is "d d d"), so the file says what the
// simulator builds.
Eigen::Vector3d SizeFor(PrimitiveShape shape, const Eigen::Vector3d& size);

// `fields` without those that mean nothing beside their siblings' current
// values (FieldInfo::shown_when: the directional frictions while
// `directional` is off, the single friction while it is on), so the
// inspector offers no parameter that does nothing.
std::vector<FieldRef> WithoutUnused(std::vector<FieldRef> fields);

}  // namespace mrsim::studio
