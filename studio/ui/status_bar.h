// The bar over the 3-D view: the file name (* when unsaved), the Run
// panel switch, and the last note, refusal or preview error (the mouse
// hints when there is none).
#pragma once

#include "studio/ui/panel.h"
#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class StatusBar {
 public:
  void Draw(StudioContext& studio, const PanelRect& rect);
};

}  // namespace mrsim::studio
