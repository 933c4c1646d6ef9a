// The left column of the studio window: file buttons, recent files, the
// easy-mode palette (pitch, yaw and sensor modules added after the
// selection, at the front or the tail), the chain as a list in its parts'
// colours, scene objects, terrain, fluids, contact pairs and the settings.
#pragma once

#include "studio/ui/widgets/panel.h"
#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class DesignPanel {
 public:
  void Draw(StudioContext& studio, const PanelRect& rect);

 private:
  Where where_ = Where::kAfterSelection;  // where the next part goes
};

}  // namespace mrsim::studio
