// Fields a file may carry that place or change nothing in the simulation
// (REQ-1.4.5): the original's Euler `rotation` beside the quaternion that
// places the part, a sensor module's lock positions and its force plate's
// pose (both follow from the face), a ray's sampling step (rays are cast
// exactly) and a hinge's breakForce (only locks break). Files that have
// them still load and keep them; the inspector does not offer them.
#pragma once

#include <string>
#include <vector>

#include "studio/design/schema.h"

namespace mrsim::studio {

// `fields` without those whose xml name is in `inert`.
std::vector<FieldRef> WithoutInert(std::vector<FieldRef> fields,
                                   const std::vector<std::string>& inert);

// `fields` without those that mean nothing beside their siblings' current
// values (FieldInfo::shown_when: the directional frictions while
// `directional` is off, the single friction while it is on), so the
// inspector offers no parameter that does nothing.
std::vector<FieldRef> WithoutUnused(std::vector<FieldRef> fields);

}  // namespace mrsim::studio
