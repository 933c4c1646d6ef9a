// The Optimise section's task picker: optimise on the design (the default)
// or on a task of the suite (docs/tasks.md), whose world, fitness and gait
// mrsim-opt then takes with --task instead of the design file.
#pragma once

#include <string>

#include "studio/ui/widgets/layout_recorder.h"

namespace mrsim::studio {

class TaskPicker {
 public:
  // Draws the combo ("the design" and every task name) with a tooltip
  // saying what the picked task scores; the combo is recorded in `layout`
  // as "task", its rows as "task <name>" and "task (the design)".
  void Draw(LayoutRecorder* layout = nullptr);
  // The picked task's name; empty: the design.
  const std::string& task() const { return task_; }
  // Picks task `name` (empty: the design), as choosing it in the combo.
  void Pick(const std::string& name);

 private:
  std::string task_;
  std::string about_;  // the tooltip: what the task scores, its gait
};

}  // namespace mrsim::studio
