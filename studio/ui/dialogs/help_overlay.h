// F1: the keys and mouse gestures of the studio window.
#pragma once

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class HelpOverlay {
 public:
  void Draw(StudioContext& studio);
};

}  // namespace mrsim::studio
