#include "studio/ui/dialogs/print_section.h"

#include <imgui.h>
#include <mujoco/mujoco.h>

#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/export/stl_export.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

void DrawPrintSection(StudioContext& studio) {
  ImGui::Separator();
  const float w = ImGui::GetContentRegionAvail().x;
  for (size_t i = 0; i < studio.oversized_meshes.size(); ++i) {
    // Before the overlaps such a mesh causes. Most CAD programs export
    // millimetres; MuJoCo reads metres, so such a
    // module is silently 1000 times too big.
    const Design::OversizedMesh& mesh = studio.oversized_meshes[i];
    const std::string name =
        IsEmbeddedMesh(mesh.shape)
            ? std::string("an embedded mesh")
            : std::filesystem::path(mesh.shape).filename().string();
    ImGui::PushID(static_cast<int>(i));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.75f, 0.3f, 1));
    ImGui::TextWrapped("%s is %.3g m across: this looks like millimetres.",
                       name.c_str(), mesh.longest);
    ImGui::PopStyleColor();
    if (studio.Button("scale by 0.001", -1)) {
      studio.Try("scale " + name + " by 0.001",
                 [&] { studio.design.ScaleMesh(mesh.shape, 0.001); });
    }
    ImGui::PopID();
  }
  if (!studio.overlaps.empty()) {
    // REQ-1.2.8: what overlaps is said here and drawn red in the 3-D view.
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
    ImGui::TextWrapped(
        "%zu overlap%s at the start (drawn red):", studio.overlaps.size(),
        studio.overlaps.size() == 1 ? "" : "s");
    for (const PartOverlap& o : studio.overlaps) {
      ImGui::TextWrapped("  %s / %s: %.1f mm", o.first.c_str(),
                         o.second.c_str(), o.depth * 1000);
    }
    ImGui::PopStyleColor();
  }
  const Selection& sel = studio.design.selection();
  if (sel.kind == SelectionKind::kModule) {
    const float half = (w - 8) / 2;
    if (studio.Button("Mesh for module...", half)) {
      studio.browse_for = BrowseFor::kFrameMesh;
      studio.browser.Open("Mesh for this module's frames (OBJ or STL)",
                          studio.StartFolder(), ".stl|.obj", false);
    }
    ImGui::SameLine();
    if (studio.Button("Mesh for all of kind...", half)) {
      studio.browse_for = BrowseFor::kKindMesh;
      studio.browser.Open("Mesh for every module of this kind (OBJ or STL)",
                          studio.StartFolder(), ".stl|.obj", false);
    }
  }
  if (studio.Button("Export STL...", -1)) {
    studio.browse_for = BrowseFor::kExportStl;
    // A folder named after the design, beside it, unless another is typed.
    const std::string path = studio.design.path();
    const std::string stem =
        path.empty() ? "robot" : std::filesystem::path(path).stem().string();
    studio.browser.Open("Export STL into a folder (type its name)",
                        studio.StartFolder(), "", true, stem + "_stl");
  }
}

void UsePrintFile(StudioContext& studio, const std::string& chosen) {
  switch (studio.browse_for) {
    case BrowseFor::kExportStl: {
      std::string done;
      studio.Try("export STL", [&] {
        const StlExport result = ExportStl(studio.design.scenario());
        WriteStlExport(result, chosen);
        int count = 0;
        for (const PrintedPart& p : result.parts) count += p.count;
        done = "exported " + std::to_string(count) + " parts (" +
               std::to_string(result.parts.size()) + " distinct) to " + chosen;
      });
      // Said after Try, which clears the message when the edit succeeds.
      if (!done.empty()) studio.Note(done);
      break;
    }
    case BrowseFor::kFrameMesh:
    case BrowseFor::kKindMesh:
      studio.Try("use the mesh", [&] {
        studio.design.SetModuleMesh(chosen,
                                    studio.browse_for == BrowseFor::kKindMesh);
      });
      break;
    default:
      break;
  }
}

void CheckOverlaps(StudioContext& studio, const Scenario& shown) {
  studio.overlaps.clear();
  std::vector<int> bodies;
  const mjModel* m = studio.preview->model();
  if (m != nullptr && studio.build_error.empty()) {
    try {
      studio.overlaps = FindOverlapsInModel(shown, m);
    } catch (const std::exception&) {
      // No data for the check: the preview still shows the design.
    }
    for (const PartOverlap& o : studio.overlaps) {
      for (const std::string& name : {o.first_body, o.second_body}) {
        const int id = mj_name2id(m, mjOBJ_BODY, name.c_str());
        if (id > 0) bodies.push_back(id);  // never the world (terrain)
      }
    }
  }
  studio.preview->SetFlaggedBodies(std::move(bodies));
}

}  // namespace mrsim::studio
