#include "studio/app/headless_studio.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "studio/design/panel_layout.h"
#include "studio/ui/widgets/gui_setup.h"

namespace mrsim::studio {

HeadlessStudio::HeadlessStudio(StudioApp* app, int width, int height)
    : app_(app), width_(width), height_(height) {
  const float scale = ChooseUiScale(app->requested_ui_scale(), 1);
  app->SetUiScale(scale);
  if (!SetUpImGui(scale)) {
    throw std::runtime_error("cannot start ImGui's OpenGL3 renderer");
  }
}

HeadlessStudio::~HeadlessStudio() { ShutDownImGui(); }

void HeadlessStudio::Frame() {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize =
      ImVec2(static_cast<float>(width_), static_cast<float>(height_));
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  app_->Frame(width_, height_, true);
  glFinish();
}

void HeadlessStudio::SavePng(const std::string& path) {
  std::vector<unsigned char> rgb;
  app_->preview().ReadPixels(width_, height_, &rgb);
  const cv::Mat image(height_, width_, CV_8UC3, rgb.data());
  cv::Mat flipped, bgr;
  cv::flip(image, flipped, 0);
  cv::cvtColor(flipped, bgr, cv::COLOR_RGB2BGR);
  bool ok = false;
  try {
    // Smallest file (docs keep these): zlib level 9.
    ok = cv::imwrite(path, bgr, {cv::IMWRITE_PNG_COMPRESSION, 9});
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw std::runtime_error("cannot write '" + path + "'");
}

void SaveScreenshot(StudioApp* app, int width, int height,
                    const std::string& path, const std::vector<int>& drag) {
  HeadlessStudio headless(app, width, height);
  for (int i = 0; i < 3; ++i) headless.Frame();
  if (drag.size() == 4) {
    ImGuiIO& io = ImGui::GetIO();
    const ImVec2 from(static_cast<float>(drag[0]), static_cast<float>(drag[1]));
    const ImVec2 to(static_cast<float>(drag[2]), static_cast<float>(drag[3]));
    // Hover first (ImGui finds the item under the mouse from the frame
    // before), press, then small steps: past the drag threshold, and each
    // move seen by the drag source and the targets on the way.
    io.MousePos = from;
    headless.Frame();
    io.MouseDown[0] = true;
    headless.Frame();
    constexpr int kSteps = 12;
    for (int i = 1; i <= kSteps; ++i) {
      const float t = static_cast<float>(i) / kSteps;
      io.MousePos =
          ImVec2(from.x + t * (to.x - from.x), from.y + t * (to.y - from.y));
      headless.Frame();
    }
    headless.Frame();  // the last place drawn with everything settled
  }
  headless.SavePng(path);
}

}  // namespace mrsim::studio
