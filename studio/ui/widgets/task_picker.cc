#include "studio/ui/widgets/task_picker.h"

#include <imgui.h>

#include <exception>

#include "optimizer/episode/task.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void TaskPicker::Draw(LayoutRecorder* layout) {
  ImGui::SetNextItemWidth(120);
  if (ImGui::BeginCombo("task",
                        task_.empty() ? "(the design)" : task_.c_str())) {
    if (ImGui::Selectable("(the design)", task_.empty())) Pick("");
    RecordItem(layout, "task (the design)");
    for (const std::string& name : TaskNames()) {
      if (ImGui::Selectable(name.c_str(), name == task_)) Pick(name);
      RecordItem(layout, "task " + name);
    }
    ImGui::EndCombo();
  }
  // The combo itself (after EndCombo, ImGui gives its item back).
  RecordItem(layout, "task");
  if (ImGui::IsItemHovered()) {
    if (task_.empty()) {
      ImGui::SetTooltip(
          "Optimise on the design (saved to its file).\n"
          "A task of the suite brings its own world, fitness and gait.");
    } else {
      ImGui::SetTooltip("%s", about_.c_str());
    }
  }
}

void TaskPicker::Pick(const std::string& name) {
  task_ = name;
  about_.clear();
  if (name.empty()) return;
  // Built once here, not per frame: the rubble's height map takes a while.
  try {
    const Task t = MakeTask(name);
    about_ = t.description + "\nits gait: " + t.gait.name + " (robot '" +
             kTaskRobot + "')";
  } catch (const std::exception& e) {
    about_ = e.what();
  }
}

}  // namespace mrsim::studio
