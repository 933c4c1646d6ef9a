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
#include "studio/ui/gui_setup.h"

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
    ok = cv::imwrite(path, bgr);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw std::runtime_error("cannot write '" + path + "'");
}

void SaveScreenshot(StudioApp* app, int width, int height,
                    const std::string& path) {
  HeadlessStudio headless(app, width, height);
  for (int i = 0; i < 3; ++i) headless.Frame();
  headless.SavePng(path);
}

}  // namespace mrsim::studio
