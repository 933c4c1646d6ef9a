// Drag and drop in the Design panel: a chain row dragged onto another row
// moves that part there, a pitch/yaw/sensor button of the palette dragged
// into the chain list (or onto the robot in the 3-D view, ground_handles.h)
// inserts a new part where it is dropped. A drop lands between the two
// parts under the cursor: above the middle of a row, in front of it; below,
// behind it. What a drop does to the design is Design::MovePart /
// InsertPart; this file only speaks ImGui's drag and drop.
#pragma once

#include "studio/design/design.h"
#include "studio/ui/studio_context.h"

namespace mrsim::studio {

// ImGui payload types.
inline constexpr const char* kChainPartPayload = "MRSIM_CHAIN_PART";
inline constexpr const char* kNewPartPayload = "MRSIM_NEW_PART";

// A chain part being dragged: its robot and place front to back.
struct ChainPartDrag {
  int robot = 0;
  int place = 0;
};

// Makes the last item (a palette button) a drag source of a new `part`.
void PaletteDragSource(NextPart part, const char* label);
// Makes the last item (the chain row at `place` of `robot`) a drag source
// and a drop target; a drop there edits the design (one undo step). Records
// "drag" and "drop" states for the window tests.
void ChainRowDragDrop(StudioContext& studio, int robot, int place,
                      const char* label);
// The new part being dragged from the palette (false when none).
bool DraggedNewPart(NextPart* part);

}  // namespace mrsim::studio
