// "Could not add the yaw module: ...": a refused button action, so the
// refusal cannot go unseen in the status bar.
#pragma once

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class RefusalDialog {
 public:
  void Draw(StudioContext& studio);
  bool shown() const { return shown_; }

 private:
  bool shown_ = false;
};

}  // namespace mrsim::studio
