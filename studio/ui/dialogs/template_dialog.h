// New robot from template: the options of `mrsim-scenario new` in a form;
// Create replaces the design with the generated robot.
#pragma once

#include "studio/ui/studio_context.h"

namespace mrsim::studio {

class TemplateDialog {
 public:
  TemplateDialog();
  void Draw(StudioContext& studio);

 private:
  TemplateOptions template_;
  int template_pattern_ = 2;  // ChainPattern
  int template_sensors_ = 0;  // SensorPlacement
};

}  // namespace mrsim::studio
