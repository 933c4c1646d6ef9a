// "A run is going on. Quitting stops it.": asked when the window is closed
// while the Run panel has processes, a recording or an optimisation going.
#pragma once

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class BusyQuitDialog {
 public:
  void Draw(StudioContext& studio);
  bool shown() const { return shown_; }

 private:
  bool shown_ = false;
};

}  // namespace mrsim::studio
