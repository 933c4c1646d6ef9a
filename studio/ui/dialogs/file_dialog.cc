#include "studio/ui/dialogs/file_dialog.h"

#include <exception>
#include <string>

#include "studio/ui/dialogs/print_section.h"

namespace mrsim::studio {

void FileDialog::Draw(StudioContext& studio) {
  std::string chosen;
  if (studio.browser.Draw(&chosen, &studio.layout)) {
    switch (studio.browse_for) {
      case BrowseFor::kOpen:
        studio.OpenFile(chosen);
        break;
      case BrowseFor::kSaveAs:
        try {
          studio.StoreRunSettings();
          studio.design.SaveAs(chosen, studio.embed_on_save);
          studio.recent.Add(chosen);
          studio.Note("saved " + chosen);
          if (studio.pending != Pending::kNone) studio.RunPending();
        } catch (const std::exception& e) {
          studio.Refuse(e.what());
        }
        break;
      case BrowseFor::kHeightImage:
        studio.Try([&] {
          const Scene& scene = studio.design.scenario().scene;
          studio.design.SetTerrain(chosen,
                                   scene.height > 0 ? scene.height : 0.3,
                                   scene.meters_per_pixel);
        });
        break;
      case BrowseFor::kExportStl:
      case BrowseFor::kFrameMesh:
      case BrowseFor::kKindMesh:
        UsePrintFile(studio, chosen);
        break;
      case BrowseFor::kNone:
        break;
    }
    studio.browse_for = BrowseFor::kNone;
  }
}

}  // namespace mrsim::studio
