// The bar over the 3-D view: the file name (* when unsaved), the Run
// panel switch, the View menu (show or hide each side panel, the
// full-window 3-D view, record the view to a video and the videos made),
// the Stop video button while recording, and the last note, refusal or preview
// error (the mouse hints when there is none).
#pragma once

#include "studio/ui/widgets/panel.h"
#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class StatusBar {
 public:
  void Draw(StudioContext& studio, const PanelRect& rect);

 private:
  void DrawViewMenu(StudioContext& studio);
};

}  // namespace mrsim::studio
