// The fields the inspector shows for a selected part, grouped by sub-part
// (a module's two frames and joint, a sensor module's plate and rays),
// taken from the scenario schema so no field is named twice.
#pragma once

#include <string>
#include <vector>

#include "studio/design/schema.h"
#include "studio/design/selection.h"

namespace mrsim::studio {

struct FieldGroup {
  std::string sub;    // as in FieldAddress::sub
  std::string title;  // "Front frame", "Joint", ...
  std::vector<FieldRef> fields;
};

// Pointers into `scenario`: valid until it changes. Empty for no selection
// or one out of range.
std::vector<FieldGroup> InspectorFields(Scenario& scenario,
                                        const Selection& selection);

// A field's name on screen: its schema label with the unit, e.g. "gain Kp
// (1/s)". The XML name goes to FieldTooltip.
std::string FieldLabel(const FieldInfo& info);

// A field's help, its name in the file ("in the file: <Kp>") and its
// limits, one per line.
std::string FieldTooltip(const FieldInfo& info);

// A field's text as the inspector shows it: every number with at most 10
// significant digits, so 0.009 x 3 reads 0.027, not 0.027000000000000003.
// The design keeps the exact value until the field is edited.
std::string ShortNumbers(const std::string& text);

// A frame's shape as the inspector shows it: a mesh carried in the file
// ("base64:...:link.stl") as "link.stl (embedded, 12.3 kB)" rather than its
// bytes; any other shape as it is.
std::string ShapeSummary(const std::string& shape);

}  // namespace mrsim::studio
