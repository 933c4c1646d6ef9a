#include "studio/ui/widgets/gui_setup.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cstdlib>
#include <filesystem>

namespace mrsim::studio {

bool SetUpImGui(float ui_scale) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (std::filesystem::exists(kFont)) {
    // Drawn at the scale's size (sharp), not magnified afterwards.
    io.Fonts->AddFontFromFileTTF(kFont, 15.0f * ui_scale);
  } else {
    io.FontGlobalScale = ui_scale;
  }
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 0;
  style.FrameRounding = 3;
  style.ItemSpacing = ImVec2(6, 5);
  style.ScaleAllSizes(ui_scale);
  return ImGui_ImplOpenGL3_Init("#version 130");
}

void ShutDownImGui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
}

void PreferOneSoftwareRenderThread() { setenv("LP_NUM_THREADS", "1", 0); }

}  // namespace mrsim::studio
