// The file dialog of Open, Save As and the terrain's height image: the
// file browser, and what the chosen file is then used for.
#pragma once

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class FileDialog {
 public:
  void Draw(StudioContext& studio);
};

}  // namespace mrsim::studio
