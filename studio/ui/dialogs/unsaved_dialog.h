// "The design has unsaved changes": Save, Discard or Cancel before the
// action waiting for it (new, open, quit).
#pragma once

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class UnsavedDialog {
 public:
  void Draw(StudioContext& studio);
  // Up and taking clicks (for the layout dump): not on its first frame.
  bool shown() const { return shown_; }

 private:
  bool shown_ = false;
};

}  // namespace mrsim::studio
