// The design panel's "Check and print" section: parts that overlap at the
// start (listed in red, drawn red in the 3-D view), "Export STL..." into a
// folder (stl_export.h), and mesh frames picked with the file browser for
// the selected frame or every module of its kind.
#pragma once

#include <string>

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

// Draws the section into the current ImGui window.
void DrawPrintSection(StudioContext& studio);

// The file dialog chose `chosen` for an export or a mesh (studio.browse_for
// says which).
void UsePrintFile(StudioContext& studio, const std::string& chosen);

// After the preview is rebuilt from `shown`: finds the overlaps on its
// model, keeps them in studio.overlaps and flags their bodies red.
void CheckOverlaps(StudioContext& studio, const Scenario& shown);

}  // namespace mrsim::studio
