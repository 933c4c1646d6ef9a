// The left column of the studio window: file buttons, recent files, the
// easy-mode palette (pitch, yaw and sensor modules added after the
// selection, at the front or the tail), the chain as a list in its parts'
// colours with each robot's locks, loose parts (Add loose part...), scene
// objects, terrain, fluids, contact pairs and the settings.
#pragma once

#include "studio/ui/studio_context.h"
#include "studio/ui/widgets/panel.h"

namespace mrsim::studio {

class DesignPanel {
 public:
  void Draw(StudioContext& studio, const PanelRect& rect);

 private:
  // Scrolls the list to `row` (drawn just now) when it is the selection
  // and the list has not scrolled to it yet.
  void ScrollToNewSelection(StudioContext& studio, const Selection& row);

  Where where_ = Where::kAfterSelection;  // where the next part goes
  // The lock or loose part the list last scrolled to: one newly selected
  // (attached, added) is scrolled into view once.
  Selection scrolled_to_;
};

}  // namespace mrsim::studio
