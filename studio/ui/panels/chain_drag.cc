#include "studio/ui/panels/chain_drag.h"

#include <imgui.h>

#include <cstring>
#include <string>

namespace mrsim::studio {

void PaletteDragSource(NextPart part, const char* label) {
  if (ImGui::BeginDragDropSource()) {
    const int kind = static_cast<int>(part);
    ImGui::SetDragDropPayload(kNewPartPayload, &kind, sizeof(kind));
    ImGui::Text("new %s", label);
    ImGui::EndDragDropSource();
  }
}

bool DraggedNewPart(NextPart* part) {
  const ImGuiPayload* payload = ImGui::GetDragDropPayload();
  if (payload == nullptr || !payload->IsDataType(kNewPartPayload) ||
      payload->DataSize != sizeof(int)) {
    return false;
  }
  int kind = 0;
  std::memcpy(&kind, payload->Data, sizeof(kind));
  *part = static_cast<NextPart>(kind);
  return true;
}

void ChainRowDragDrop(StudioContext& studio, int robot, int place,
                      const char* label) {
  if (ImGui::BeginDragDropSource()) {
    const ChainPartDrag drag{robot, place};
    ImGui::SetDragDropPayload(kChainPartPayload, &drag, sizeof(drag));
    ImGui::Text("move %s", label);
    ImGui::EndDragDropSource();
  }
  if (const ImGuiPayload* p = ImGui::GetDragDropPayload()) {
    if (p->IsDataType(kChainPartPayload) &&
        p->DataSize == sizeof(ChainPartDrag)) {
      ChainPartDrag drag;
      std::memcpy(&drag, p->Data, sizeof(drag));
      studio.layout.State("drag", "part " + std::to_string(drag.robot) + " " +
                                      std::to_string(drag.place));
    } else if (p->IsDataType(kNewPartPayload)) {
      studio.layout.State("drag", "new");
    }
  }
  if (!ImGui::BeginDragDropTarget()) return;
  // Between the parts under the cursor: the upper half of a row drops in
  // front of it, the lower half behind it.
  const float middle =
      (ImGui::GetItemRectMin().y + ImGui::GetItemRectMax().y) / 2;
  const int at = ImGui::GetMousePos().y < middle ? place : place + 1;
  studio.layout.State("drop", std::to_string(robot) + " " + std::to_string(at));
  // A line where the part will land.
  const float line_y =
      at == place ? ImGui::GetItemRectMin().y : ImGui::GetItemRectMax().y;
  ImGui::GetWindowDrawList()->AddLine(ImVec2(ImGui::GetItemRectMin().x, line_y),
                                      ImVec2(ImGui::GetItemRectMax().x, line_y),
                                      IM_COL32(255, 255, 255, 255), 2.0f);
  const ImGuiDragDropFlags flags = ImGuiDragDropFlags_AcceptNoDrawDefaultRect;
  if (const ImGuiPayload* p =
          ImGui::AcceptDragDropPayload(kChainPartPayload, flags)) {
    if (p->DataSize == sizeof(ChainPartDrag)) {
      ChainPartDrag drag;
      std::memcpy(&drag, p->Data, sizeof(drag));
      if (drag.robot == robot) {
        // `at` counts places with the part still in the list.
        const int to = at > drag.place ? at - 1 : at;
        studio.Try("move the part",
                   [&] { studio.design.MovePart(robot, drag.place, to); });
      } else {
        studio.message = "parts move within their own robot";
      }
    }
  }
  if (const ImGuiPayload* p =
          ImGui::AcceptDragDropPayload(kNewPartPayload, flags)) {
    if (p->DataSize == sizeof(int)) {
      int kind = 0;
      std::memcpy(&kind, p->Data, sizeof(kind));
      studio.Try("insert the part", [&] {
        studio.design.InsertPart(static_cast<NextPart>(kind), robot, at);
      });
    }
  }
  ImGui::EndDragDropTarget();
}

}  // namespace mrsim::studio
